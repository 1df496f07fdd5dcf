#include "solver_cpus.hpp"

#include <algorithm>
#include <cctype>
#include <cstddef>
#include <fstream>
#include <stdexcept>

namespace pushpull::app {
namespace {

int parse_cpu(const std::string& text) {
  if (text.empty() || text.size() > 4 || !std::all_of(text.begin(), text.end(), [](char c) {
        return std::isdigit(static_cast<unsigned char>(c));
      }))
    throw std::invalid_argument("'" + text + "' is not a CPU number (expected e.g. 1, 2-3 or 1,3)");
  const int cpu = std::stoi(text);
  if (cpu > kLargestCpu)
    throw std::invalid_argument("CPU " + text + " is too large (at most " + std::to_string(kLargestCpu) +
                                ")");
  return cpu;
}

// "1,3,5-7" -> {1, 3, 5, 6, 7}: ascending, each once. Throws std::invalid_argument naming the problem.
std::vector<int> parse_cpu_list(const std::string& spec) {
  std::vector<int> cpus;
  std::size_t start = 0;
  while (start <= spec.size()) {
    const std::size_t comma = std::min(spec.find(',', start), spec.size());
    const std::string item = spec.substr(start, comma - start);
    const std::size_t dash = item.find('-');
    const int first = parse_cpu(item.substr(0, dash));
    const int last = dash == std::string::npos ? first : parse_cpu(item.substr(dash + 1));
    if (last < first) throw std::invalid_argument("the range '" + item + "' is empty");
    for (int cpu = first; cpu <= last; ++cpu) cpus.push_back(cpu);
    start = comma + 1;
  }
  std::sort(cpus.begin(), cpus.end());
  cpus.erase(std::unique(cpus.begin(), cpus.end()), cpus.end());
  return cpus;
}

}  // namespace

std::vector<int> core_siblings(int cpu) {
  std::ifstream in("/sys/devices/system/cpu/cpu" + std::to_string(cpu) + "/topology/thread_siblings_list");
  std::string list;
  std::vector<int> cpus;
  if (in >> list) {
    try {
      cpus = parse_cpu_list(list);  // the kernel writes the same list syntax
    } catch (const std::invalid_argument&) {
      cpus.clear();
    }
  }
  if (std::find(cpus.begin(), cpus.end(), cpu) == cpus.end()) return {cpu};
  return cpus;
}

std::optional<CpuSplit> split_cpus(const std::string& spec, const std::vector<int>& allowed,
                                   const std::function<std::vector<int>(int)>& siblings) {
  if (spec == "none") return std::nullopt;
  std::vector<int> solver;
  if (spec == "auto") {
    if (allowed.size() < 2) return std::nullopt;
    const int last = allowed.back();
    for (const int cpu : siblings(last))  // its whole physical core, when others remain for the frames
      if (std::find(allowed.begin(), allowed.end(), cpu) != allowed.end()) solver.push_back(cpu);
    std::sort(solver.begin(), solver.end());
    solver.erase(std::unique(solver.begin(), solver.end()), solver.end());
    if (solver.empty() || solver.size() >= allowed.size()) solver = {last};
  } else {
    solver = parse_cpu_list(spec);
  }
  CpuSplit split;
  split.solver = solver;
  for (const int cpu : solver)
    if (std::find(allowed.begin(), allowed.end(), cpu) == allowed.end())
      throw std::invalid_argument("CPU " + std::to_string(cpu) + " is not one this process may run on (" +
                                  cpu_list_text(allowed) + ")");
  for (const int cpu : allowed)
    if (!std::binary_search(solver.begin(), solver.end(), cpu)) split.frames.push_back(cpu);
  if (split.frames.empty())
    throw std::invalid_argument("leaves no CPU for the frames (this process has " + cpu_list_text(allowed) +
                                ")");
  return split;
}

std::string cpu_list_text(const std::vector<int>& cpus) {
  std::string text;
  for (std::size_t k = 0; k < cpus.size();) {
    std::size_t end = k;
    while (end + 1 < cpus.size() && cpus[end + 1] == cpus[end] + 1) ++end;
    if (!text.empty()) text += ',';
    text += std::to_string(cpus[k]);
    if (end > k) text += '-' + std::to_string(cpus[end]);
    k = end + 1;
  }
  return text.empty() ? "none" : text;
}

}  // namespace pushpull::app
