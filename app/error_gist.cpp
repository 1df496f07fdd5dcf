#include "error_gist.hpp"

#include "pushpull/deform/method.hpp"

namespace pushpull::app {

std::string error_gist(const std::string& error) {
  std::string gist = error;
  const std::string deformer = "deformer: ";
  if (gist.rfind(deformer, 0) == 0) gist.erase(0, deformer.size());
  for (const deform::Method m : deform::kAllMethods) {  // "arap-s: the energy went negative, ..."
    const std::string prefix = std::string(deform::method_name(m)) + ": ";
    if (gist.rfind(prefix, 0) == 0) gist.erase(0, prefix.size());
  }
  const std::size_t clause = gist.find_first_of(",;:(");
  if (clause != std::string::npos) gist.erase(clause);
  while (!gist.empty() && gist.back() == ' ') gist.pop_back();
  constexpr std::size_t kLongest = 48;
  if (gist.size() > kLongest) gist = gist.substr(0, kLongest - 3) + "...";
  return gist.empty() ? "see the terminal" : gist;
}

}  // namespace pushpull::app
