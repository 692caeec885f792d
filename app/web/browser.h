// The app in a browser page (the emscripten build only): the page's animation frames drive the
// demo, and the canvas takes the size the page gives it. The rest of the app is the desktop's.
#pragma once

#include <functional>

struct GLFWwindow;

namespace softbody::app::browser {

// Calls frame() once per animation frame of the page until it returns false (or throws: the
// error goes to the console as one line), and returns at once: the page's loop goes on after
// this function and its callers have returned, so anything frame() uses must live on the heap.
// frame is kept after that (with what it holds), so that the page goes on showing the last frame.
void run_frames(std::function<bool()> frame);

// Gives the window (the page's canvas) the size the page lays it out at, in CSS pixels, when
// that has changed: the demo fills the browser's window and follows it when it is resized.
void fit_canvas(GLFWwindow* window);

}  // namespace softbody::app::browser
