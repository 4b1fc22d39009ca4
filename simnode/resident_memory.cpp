#include "simnode/resident_memory.hpp"

#include <fstream>
#include <string>

namespace olcb::simnode {

long resident_kib() {
    std::ifstream status("/proc/self/status");
    std::string key;
    while (status >> key) {
        if (key == "VmRSS:") {
            long kib = 0;
            status >> kib;
            return kib;
        }
        status.ignore(1 << 16, '\n');
    }
    return 0;
}

}  // namespace olcb::simnode
