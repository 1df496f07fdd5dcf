#include "pushpull/deform/cpu_affinity.hpp"

#ifdef __linux__
#include <sched.h>
#endif

namespace pushpull::deform {

std::vector<int> allowed_cpus() {
  std::vector<int> cpus;
#ifdef __linux__
  cpu_set_t set;
  CPU_ZERO(&set);
  if (::sched_getaffinity(0, sizeof set, &set) != 0) return cpus;
  for (int cpu = 0; cpu < CPU_SETSIZE; ++cpu)
    if (CPU_ISSET(cpu, &set)) cpus.push_back(cpu);
#endif
  return cpus;
}

bool pin_calling_thread(std::span<const int> cpus) {
  if (cpus.empty()) return true;
#ifdef __linux__
  cpu_set_t set;
  CPU_ZERO(&set);
  for (const int cpu : cpus) {
    if (cpu < 0 || cpu >= CPU_SETSIZE) return false;
    CPU_SET(cpu, &set);
  }
  return ::sched_setaffinity(0, sizeof set, &set) == 0;  // 0: the calling thread
#else
  return false;
#endif
}

}  // namespace pushpull::deform
