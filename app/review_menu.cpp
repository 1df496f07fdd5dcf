#include "review_menu.hpp"

#include <algorithm>
#include <cmath>

namespace pushpull::app {
namespace {

constexpr ReviewColour kColours[] = {ReviewColour::Material, ReviewColour::Displacement, ReviewColour::CurvatureSign};
constexpr int kMethods = int(deform::kAllMethods.size());
constexpr int kRows = kMethods + 3;

}  // namespace

void ReviewMenu::toggle(deform::Method current) {
  open_ = !open_;
  const auto it = std::find(deform::kAllMethods.begin(), deform::kAllMethods.end(), current);
  if (open_) row_ = it == deform::kAllMethods.end() ? 0 : int(it - deform::kAllMethods.begin());
  // A trigger or stick already held when the panel opens must be let go before it acts.
  stick_armed_ = trigger_armed_ = false;
}

MenuChoice ReviewMenu::update(float stick_y, float trigger) {
  MenuChoice choice;
  if (!open_) return choice;
  if (std::abs(stick_y) < 0.3f) stick_armed_ = true;
  if (stick_armed_ && std::abs(stick_y) > 0.6f) {
    row_ = (row_ + (stick_y > 0.0f ? kRows - 1 : 1)) % kRows;  // up = the row above
    stick_armed_ = false;
  }
  if (trigger < 0.2f) trigger_armed_ = true;
  if (trigger_armed_ && trigger > 0.8f) {
    trigger_armed_ = false;
    if (row_ < kMethods)
      choice.method = deform::kAllMethods[size_t(row_)];
    else
      choice.colour = kColours[row_ - kMethods];
  }
  return choice;
}

std::vector<std::string> ReviewMenu::lines(deform::Method method, ReviewColour colour) const {
  std::vector<std::string> out{"METHOD"};
  for (deform::Method m : deform::kAllMethods)
    out.push_back(std::string(m == method ? "* " : "  ") + std::string(deform::method_name(m)));
  out.push_back("COLOURS");
  for (ReviewColour c : kColours) out.push_back(std::string(c == colour ? "* " : "  ") + colour_name(c));
  out.push_back("stick: choose  trigger: apply");
  out.push_back("menu: close");
  return out;
}

int ReviewMenu::selected_line() const { return row_ < kMethods ? 1 + row_ : 2 + row_; }

}  // namespace pushpull::app
