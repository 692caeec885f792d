#include "process_memory.h"

#include <fstream>
#include <string>

namespace softbody::app {

ResidentMemory resident_memory() {
    ResidentMemory memory;
    std::ifstream status("/proc/self/status");
    for (std::string line; std::getline(status, line);) {
        if (line.rfind("VmRSS:", 0) == 0) memory.now_kib = std::stol(line.substr(6));
        if (line.rfind("VmHWM:", 0) == 0) memory.peak_kib = std::stol(line.substr(6));
    }
    return memory;
}

}  // namespace softbody::app
