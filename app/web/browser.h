// The app in a browser page (the emscripten build only): the page's animation frames drive the
// demo, the canvas takes the size the page gives it at the screen's own pixel density, the
// page's fingers and files come in, and links, clipboard and downloads go out. The rest of the
// app is the desktop's.
#pragma once

#include <functional>
#include <string>
#include <vector>

struct GLFWwindow;

namespace softbody::app::browser {

// Calls frame() once per animation frame of the page until it returns false (or throws: the
// error goes to the console as one line), and returns at once: the page's loop goes on after
// this function and its callers have returned, so anything frame() uses must live on the heap.
// frame is kept after that (with what it holds), so that the page goes on showing the last frame.
void run_frames(std::function<bool()> frame);

// Gives the canvas as many pixels as it covers on the screen (its CSS size times the device's
// pixel ratio) and the window that size, when either has changed: the demo fills the browser's
// window, follows it when it is resized, and is drawn at the screen's own density. The page's
// GLFW is not asked to resize: when the size equals the screen's it asks for fullscreen
// instead, and the canvas keeps its old size, stretched.
void fit_canvas(GLFWwindow* window);
// Device pixels per CSS pixel (2 on most phones and tablets): the UI's scale.
float pixel_ratio();
// Whether the page is on a screen that takes fingers (a tablet, a phone, a touch laptop).
bool touch_screen();

// Fingers on the canvas: the page's pointer events (web/softbody-page.js) call
// handler(phase, id, x, y), phase 0 down, 1 move, 2 up, 3 cancelled, x and y in the canvas's
// pixels. The page's GLFW sees no touches (it would take them as clicks without a position).
void on_touch(std::function<void(int phase, int id, float x, float y)> handler);
// The page's question "what is the app showing?" (the browser tests ask it): JSON.
void on_state(std::function<std::string()> answer);
// Where and what the panel's items were in the frame just drawn, as a JSON array of
// {"label", "window", "x", "y", "w", "h"} in the canvas's pixels (the tests tap them by name):
// the items shown, each label as it reads (a window's fold arrow as "#COLLAPSE"); an item
// scrolled out of sight has no label and is left out.
std::string ui_items_json();

// Files the person chose with choose_file(), put in the page's file system, each taken once.
std::vector<std::string> take_chosen_files();
// Opens the browser's file picker (a browser allows that just after a click or a tap).
void choose_file(const std::string& accept);
// The page's address without its query (https://host/path/index.html): where a link starts.
std::string page_address();
// Puts text on the clipboard (a browser allows that just after a click or a tap). The browser
// answers later: take_copy_failure() is true once when it refused.
void copy_text(const std::string& text);
bool take_copy_failure();
// Hands text to the browser as a file download named `name`.
void download(const std::string& name, const std::string& text, const std::string& type);
// Stores the presets folder in the browser (the page mounts it there: web/softbody-page.js)
// now; run_frames also does so by itself within a second of any change to it.
void store_presets();

}  // namespace softbody::app::browser
