// The process's resident memory, for the soak runs' "memory stays flat" (softbody run's summary
// and softbody render's JSON lines).
#pragma once

namespace softbody::app {

struct ResidentMemory {
    long now_kib = -1;   // VmRSS: resident now
    long peak_kib = -1;  // VmHWM: the most it has been resident
};

// Read from /proc/self/status; -1 where the system does not say (not Linux).
ResidentMemory resident_memory();

}  // namespace softbody::app
