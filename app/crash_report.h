// A crash says where it happened: on a fatal signal (a bad memory access, an abort from a
// corrupted heap, a bad instruction) the process writes one line naming the signal and then its
// call stack to stderr, and ends by that signal as it would have. A crash that came once, in
// one test run of many, can then be traced from its log alone: each frame of softbody itself
// is an offset in the executable, which `addr2line -C -f -e softbody OFFSET` names.
#pragma once

namespace softbody::app {

// Installs the report for SIGSEGV, SIGBUS, SIGFPE, SIGILL and SIGABRT. Nothing where the system
// cannot list a call stack, and nothing in a build with a sanitizer (its own report says more).
void install_crash_report();

}  // namespace softbody::app
