#include "profiles.hpp"

#include <openxr/openxr.h>

#include <cctype>

namespace pushpull::xrsim {
namespace {

using K = ComponentKind;
struct Spec {
  const char* sub;  // component below the user path
  K kind;
};

void add(InteractionProfile& p, const char* user, std::initializer_list<Spec> specs) {
  for (const Spec& s : specs) p.components.push_back({std::string(user) + s.sub, s.kind});
}

std::vector<InteractionProfile> make_profiles() {
  std::vector<InteractionProfile> all;
  const char* L = "/user/hand/left";
  const char* R = "/user/hand/right";
  const Spec poses[] = {
      {"/input/grip/pose", K::pose}, {"/input/aim/pose", K::pose}, {"/output/haptic", K::haptic}};
  // Windows Mixed Reality motion controllers (Microsoft's, Samsung's Odyssey): their components on each hand.
  const std::initializer_list<Spec> kMotion = {
      {"/input/menu/click", K::boolean},       {"/input/squeeze/click", K::boolean},
      {"/input/trigger/value", K::scalar},     {"/input/thumbstick", K::vector2},
      {"/input/thumbstick/x", K::scalar},      {"/input/thumbstick/y", K::scalar},
      {"/input/thumbstick/click", K::boolean}, {"/input/trackpad", K::vector2},
      {"/input/trackpad/x", K::scalar},        {"/input/trackpad/y", K::scalar},
      {"/input/trackpad/click", K::boolean},   {"/input/trackpad/touch", K::boolean}};
  const auto both = [&](InteractionProfile& p, std::initializer_list<Spec> specs) {
    for (const char* u : {L, R}) {
      add(p, u, specs);
      for (const Spec& s : poses) p.components.push_back({std::string(u) + s.sub, s.kind});
    }
  };
  {
    InteractionProfile p{
        "/interaction_profiles/khr/simple_controller", "Khronos Simple Controller", {L, R}, {}, {}};
    both(p, {{"/input/select/click", K::boolean}, {"/input/menu/click", K::boolean}});
    all.push_back(p);
  }
  {
    InteractionProfile p{
        "/interaction_profiles/oculus/touch_controller", "Oculus Touch Controller", {L, R}, {}, {}};
    both(p, {{"/input/squeeze/value", K::scalar},
             {"/input/trigger/value", K::scalar},
             {"/input/trigger/touch", K::boolean},
             {"/input/thumbstick", K::vector2},
             {"/input/thumbstick/x", K::scalar},
             {"/input/thumbstick/y", K::scalar},
             {"/input/thumbstick/click", K::boolean},
             {"/input/thumbstick/touch", K::boolean},
             {"/input/thumbrest/touch", K::boolean}});
    add(p, L,
        {{"/input/x/click", K::boolean},
         {"/input/x/touch", K::boolean},
         {"/input/y/click", K::boolean},
         {"/input/y/touch", K::boolean},
         {"/input/menu/click", K::boolean}});
    add(p, R,
        {{"/input/a/click", K::boolean},
         {"/input/a/touch", K::boolean},
         {"/input/b/click", K::boolean},
         {"/input/b/touch", K::boolean},
         {"/input/system/click", K::boolean}});
    all.push_back(p);
  }
  {
    InteractionProfile p{
        "/interaction_profiles/valve/index_controller", "Valve Index Controller", {L, R}, {}, {}};
    both(p, {{"/input/system/click", K::boolean},     {"/input/system/touch", K::boolean},
             {"/input/a/click", K::boolean},          {"/input/a/touch", K::boolean},
             {"/input/b/click", K::boolean},          {"/input/b/touch", K::boolean},
             {"/input/squeeze/value", K::scalar},     {"/input/squeeze/force", K::scalar},
             {"/input/trigger/click", K::boolean},    {"/input/trigger/value", K::scalar},
             {"/input/trigger/touch", K::boolean},    {"/input/thumbstick", K::vector2},
             {"/input/thumbstick/x", K::scalar},      {"/input/thumbstick/y", K::scalar},
             {"/input/thumbstick/click", K::boolean}, {"/input/thumbstick/touch", K::boolean},
             {"/input/trackpad", K::vector2},         {"/input/trackpad/x", K::scalar},
             {"/input/trackpad/y", K::scalar},        {"/input/trackpad/force", K::scalar},
             {"/input/trackpad/touch", K::boolean}});
    all.push_back(p);
  }
  {
    InteractionProfile p{"/interaction_profiles/htc/vive_controller", "HTC Vive Controller", {L, R}, {}, {}};
    both(p, {{"/input/system/click", K::boolean},
             {"/input/squeeze/click", K::boolean},
             {"/input/menu/click", K::boolean},
             {"/input/trigger/click", K::boolean},
             {"/input/trigger/value", K::scalar},
             {"/input/trackpad", K::vector2},
             {"/input/trackpad/x", K::scalar},
             {"/input/trackpad/y", K::scalar},
             {"/input/trackpad/click", K::boolean},
             {"/input/trackpad/touch", K::boolean}});
    all.push_back(p);
  }
  {
    InteractionProfile p{"/interaction_profiles/microsoft/motion_controller",
                         "Microsoft Mixed Reality Motion Controller",
                         {L, R},
                         {},
                         {}};
    both(p, kMotion);
    all.push_back(p);
  }
  // The extensions' profiles, after the core ones (the default choice stays the core profile).
  {
    InteractionProfile p{"/interaction_profiles/hp/mixed_reality_controller",
                         "HP Mixed Reality Controller",
                         {L, R},
                         {},
                         XR_EXT_HP_MIXED_REALITY_CONTROLLER_EXTENSION_NAME};
    both(p, {{"/input/menu/click", K::boolean},
             {"/input/squeeze/value", K::scalar},
             {"/input/trigger/value", K::scalar},
             {"/input/thumbstick", K::vector2},
             {"/input/thumbstick/x", K::scalar},
             {"/input/thumbstick/y", K::scalar},
             {"/input/thumbstick/click", K::boolean}});
    add(p, L, {{"/input/x/click", K::boolean}, {"/input/y/click", K::boolean}});
    add(p, R, {{"/input/a/click", K::boolean}, {"/input/b/click", K::boolean}});
    all.push_back(p);
  }
  {
    InteractionProfile p{"/interaction_profiles/htc/vive_cosmos_controller",
                         "HTC Vive Cosmos Controller",
                         {L, R},
                         {},
                         XR_HTC_VIVE_COSMOS_CONTROLLER_INTERACTION_EXTENSION_NAME};
    both(p, {{"/input/shoulder/click", K::boolean},
             {"/input/squeeze/click", K::boolean},
             {"/input/trigger/click", K::boolean},
             {"/input/trigger/value", K::scalar},
             {"/input/thumbstick", K::vector2},
             {"/input/thumbstick/x", K::scalar},
             {"/input/thumbstick/y", K::scalar},
             {"/input/thumbstick/click", K::boolean},
             {"/input/thumbstick/touch", K::boolean}});
    add(p, L,
        {{"/input/x/click", K::boolean}, {"/input/y/click", K::boolean}, {"/input/menu/click", K::boolean}});
    add(p, R,
        {{"/input/a/click", K::boolean},
         {"/input/b/click", K::boolean},
         {"/input/system/click", K::boolean}});
    all.push_back(p);
  }
  {
    InteractionProfile p{"/interaction_profiles/samsung/odyssey_controller",
                         "Samsung Odyssey Controller",
                         {L, R},
                         {},
                         XR_EXT_SAMSUNG_ODYSSEY_CONTROLLER_EXTENSION_NAME};
    both(p, kMotion);  // the motion controller's components
    all.push_back(p);
  }
  return all;
}

const ProfileComponent* find_component(const InteractionProfile& profile, const std::string& path) {
  for (const auto& c : profile.components)
    if (c.path == path) return &c;
  return nullptr;
}

std::string capitalize(std::string s) {
  bool start = true;
  for (char& c : s) {
    if (c == '_' || c == ' ') {
      c = ' ';
      start = true;
    } else if (start) {
      c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
      start = false;
    }
  }
  return s;
}

}  // namespace

const std::vector<InteractionProfile>& interaction_profiles() {
  static const std::vector<InteractionProfile> profiles = make_profiles();
  return profiles;
}

bool profile_extension(const char* extension) {
  for (const auto& p : interaction_profiles())
    if (!p.extension.empty() && p.extension == extension) return true;
  return false;
}

const InteractionProfile* find_profile(const std::string& path) {
  for (const auto& p : interaction_profiles())
    if (p.path == path) return &p;
  return nullptr;
}

const ProfileComponent* resolve_binding(const InteractionProfile& profile, const std::string& path,
                                        ComponentKind preferred) {
  if (const ProfileComponent* c = find_component(profile, path)) return c;
  // An identifier without component: pick the component that suits the action type.
  std::vector<const char*> order;
  switch (preferred) {
    case K::boolean:
      order = {"/click", "/value", "/force"};
      break;
    case K::scalar:
      order = {"/value", "/force", "/click"};
      break;
    case K::vector2:
      order = {};
      break;
    case K::pose:
      order = {"/pose"};
      break;
    case K::haptic:
      order = {};
      break;
  }
  for (const char* suffix : order)
    if (const ProfileComponent* c = find_component(profile, path + suffix)) return c;
  return nullptr;
}

std::string user_path_of(const InteractionProfile& profile, const std::string& binding_path) {
  for (const auto& u : profile.user_paths)
    if (binding_path.compare(0, u.size(), u) == 0 && binding_path.size() > u.size() &&
        binding_path[u.size()] == '/')
      return u;
  return {};
}

std::string localized_user_path(const std::string& user_path) {
  if (user_path == "/user/hand/left") return "Left Hand";
  if (user_path == "/user/hand/right") return "Right Hand";
  if (user_path == "/user/head") return "Head";
  if (user_path == "/user/gamepad") return "Gamepad";
  return user_path;
}

std::string localized_component(const std::string& component_path) {
  // ".../input/<identifier>[/<component>]" -> "<Identifier> [<Component>]"
  auto pos = component_path.find("/input/");
  std::size_t skip = 7;
  if (pos == std::string::npos) {
    pos = component_path.find("/output/");
    skip = 8;
  }
  if (pos == std::string::npos) return component_path;
  std::string rest = component_path.substr(pos + skip);
  for (char& c : rest)
    if (c == '/') c = ' ';
  return capitalize(rest);
}

}  // namespace pushpull::xrsim
