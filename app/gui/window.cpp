#include "gui/window.h"

#include <glad/gl.h>  // before GLFW, which then includes no GL header of its own
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <imgui.h>
#include <imgui_impl_glfw.h>
#include <imgui_impl_opengl3.h>

#include <algorithm>
#include <stdexcept>

#if defined(__EMSCRIPTEN__)
#include "web/browser.h"
#endif

namespace softbody::app {

namespace {

std::string g_glfw_error;  // GLFW reports errors through a C callback without user data

void on_glfw_error(int, const char* description) { g_glfw_error = description ? description : "unknown error"; }

}  // namespace

// GLFW's C callbacks, installed before ImGui's backend (which then chains to them).
struct WindowCallbacks {
    static Window& self(GLFWwindow* w) { return *static_cast<Window*>(glfwGetWindowUserPointer(w)); }
    static InputEvent with_modifiers(GLFWwindow* w, InputEvent e) {
        e.shift = glfwGetKey(w, GLFW_KEY_LEFT_SHIFT) == GLFW_PRESS || glfwGetKey(w, GLFW_KEY_RIGHT_SHIFT) == GLFW_PRESS;
        e.ctrl = glfwGetKey(w, GLFW_KEY_LEFT_CONTROL) == GLFW_PRESS || glfwGetKey(w, GLFW_KEY_RIGHT_CONTROL) == GLFW_PRESS;
        return e;
    }
    static void drop(GLFWwindow* w, int count, const char** paths) {
        for (int i = 0; i < count; ++i) self(w).dropped_.emplace_back(paths[i]);
    }
    static void cursor(GLFWwindow* w, double x, double y) {
        int width = 1, height = 1;
        glfwGetWindowSize(w, &width, &height);
        Window& win = self(w);
        win.cursor_x_ = static_cast<float>(x / std::max(width, 1));
        win.cursor_y_ = static_cast<float>(y / std::max(height, 1));
        InputEvent e;
        e.type = InputEvent::Type::Move;
        e.x = win.cursor_x_;
        e.y = win.cursor_y_;
        win.events_.push_back(e);
    }
    static void button(GLFWwindow* w, int button, int action, int) {
        if (button > 2) return;
        Window& win = self(w);
        InputEvent e;
        e.type = action == GLFW_PRESS ? InputEvent::Type::Press : InputEvent::Type::Release;
        e.button = button == GLFW_MOUSE_BUTTON_LEFT ? 0 : button == GLFW_MOUSE_BUTTON_RIGHT ? 1 : 2;
        e.x = win.cursor_x_;
        e.y = win.cursor_y_;
        win.events_.push_back(with_modifiers(w, e));
    }
    static void scroll(GLFWwindow* w, double, double dy) {
        InputEvent e;
        e.type = InputEvent::Type::Scroll;
        e.scroll = static_cast<float>(dy);
        self(w).events_.push_back(e);
    }
    static void key(GLFWwindow* w, int key, int, int action, int) {
        if (action != GLFW_PRESS) return;
        InputEvent e;
        e.type = InputEvent::Type::Key;
        e.key = key;
        self(w).events_.push_back(with_modifiers(w, e));
    }
};

Window::Window(const WindowOptions& options) {
    glfwSetErrorCallback(on_glfw_error);
    if (!glfwInit()) {
        throw std::runtime_error("cannot open a window: " +
                                 (g_glfw_error.empty() ? std::string("no display") : g_glfw_error) +
                                 " (the demo needs a desktop session; headless: 'softbody render')");
    }
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
#if !defined(__EMSCRIPTEN__)  // the browser's GLFW (3.2) has no content scale: the page is in CSS pixels
    glfwWindowHint(GLFW_SCALE_TO_MONITOR, GLFW_TRUE);
#endif
    glfwWindowHint(GLFW_VISIBLE, options.visible ? GLFW_TRUE : GLFW_FALSE);
    window_ = glfwCreateWindow(options.width, options.height, options.title.c_str(), nullptr, nullptr);
    if (!window_) {
        glfwTerminate();
        throw std::runtime_error("cannot create an OpenGL 3.3 core window: " + g_glfw_error);
    }
    glfwMakeContextCurrent(window_);
#if defined(__EMSCRIPTEN__)
    browser::fit_canvas(window_);  // the page's layout gives the size, before anything is framed in it
#endif
    glfwSwapInterval(options.vsync ? 1 : 0);
    if (!gladLoadGL(reinterpret_cast<GLADloadfunc>(glfwGetProcAddress))) {
        glfwDestroyWindow(window_);
        glfwTerminate();
        throw std::runtime_error("cannot load OpenGL 3.3 core functions in this window");
    }
    glfwSetWindowUserPointer(window_, this);
    glfwSetDropCallback(window_, WindowCallbacks::drop);
    glfwSetCursorPosCallback(window_, WindowCallbacks::cursor);
    glfwSetMouseButtonCallback(window_, WindowCallbacks::button);
    glfwSetScrollCallback(window_, WindowCallbacks::scroll);
    glfwSetKeyCallback(window_, WindowCallbacks::key);

#if !defined(__EMSCRIPTEN__)
    float sx = 1.0f, sy = 1.0f;
    glfwGetWindowContentScale(window_, &sx, &sy);
    content_scale_ = sx > 0.5f ? sx : 1.0f;
#endif

    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGuiIO& io = ImGui::GetIO();
    io.IniFilename = nullptr;  // the layout is set in code; nothing is written behind the user's back
    io.ConfigFlags |= ImGuiConfigFlags_NavEnableKeyboard;  // Tab and the arrows move through the panel
    ImGui::StyleColorsDark();
    ImGuiStyle& style = ImGui::GetStyle();
    style.WindowRounding = 6.0f;
    style.FrameRounding = 4.0f;
    style.GrabRounding = 4.0f;
    style.WindowBorderSize = 0.0f;
    style.Colors[ImGuiCol_WindowBg].w = 0.90f;
    style.ScaleAllSizes(content_scale_);
    ImFontConfig font;
    font.SizePixels = 14.0f * content_scale_;
    io.Fonts->AddFontDefault(&font);
    ImGui_ImplGlfw_InitForOpenGL(window_, true);
#if defined(__EMSCRIPTEN__)
    ImGui_ImplOpenGL3_Init("#version 300 es");  // WebGL2
#else
    ImGui_ImplOpenGL3_Init("#version 330 core");
#endif
}

Window::~Window() {
    ImGui_ImplOpenGL3_Shutdown();
    ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext();
    glfwDestroyWindow(window_);
    glfwTerminate();
}

bool Window::should_close() const { return glfwWindowShouldClose(window_); }
void Window::request_close() { glfwSetWindowShouldClose(window_, GLFW_TRUE); }
void Window::poll_events() {
#if defined(__EMSCRIPTEN__)
    browser::fit_canvas(window_);  // the page's events arrive by themselves; its layout may have changed
#endif
    glfwPollEvents();
}
void Window::swap_buffers() { glfwSwapBuffers(window_); }
double Window::time() const { return glfwGetTime(); }

int Window::framebuffer_width() const {
    int w = 0, h = 0;
    glfwGetFramebufferSize(window_, &w, &h);
    return w;
}

int Window::framebuffer_height() const {
    int w = 0, h = 0;
    glfwGetFramebufferSize(window_, &w, &h);
    return h;
}

std::vector<InputEvent> Window::take_events() {
    std::vector<InputEvent> events;
    events.swap(events_);
    return events;
}

std::vector<std::string> Window::take_dropped_files() {
    std::vector<std::string> files;
    files.swap(dropped_);
    return files;
}

void Window::begin_ui_frame() {
    ImGui_ImplOpenGL3_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    ImGui::NewFrame();
}

void Window::end_ui_frame() {
    ImGui::Render();
    glViewport(0, 0, framebuffer_width(), framebuffer_height());
    ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
}

}  // namespace softbody::app
