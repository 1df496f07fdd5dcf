// The interaction profiles the simulated runtime accepts bindings for, with their input and output
// components. Immutable tables; thread-safe.
#pragma once

#include <string>
#include <vector>

namespace pushpull::xrsim {

enum class ComponentKind { boolean, scalar, vector2, pose, haptic };

struct ProfileComponent {
  std::string path;  // full path, e.g. "/user/hand/left/input/menu/click"
  ComponentKind kind;
};

struct InteractionProfile {
  std::string path;            // e.g. "/interaction_profiles/khr/simple_controller"
  std::string localized_name;  // e.g. "Khronos Simple Controller"
  std::vector<std::string> user_paths;
  std::vector<ProfileComponent> components;
  // The instance extension that brings the profile ("" for OpenXR 1.0's): without it enabled the profile
  // path is unsupported (xrSuggestInteractionProfileBindings: XR_ERROR_PATH_UNSUPPORTED).
  std::string extension;
};

// All supported profiles, in the order the runtime prefers them when several have bindings.
const std::vector<InteractionProfile>& interaction_profiles();
const InteractionProfile* find_profile(const std::string& path);
// Whether `extension` is one that brings a profile (offered unless the no-controller-extensions quirk).
bool profile_extension(const char* extension);

// The component a suggested binding path names in `profile`: the path itself, or for an identifier
// without component ("/user/hand/left/input/trigger") the component matching `preferred` (the action
// type; /value, /click, /pose or the vector2 itself). nullptr when the profile has no such input.
const ProfileComponent* resolve_binding(const InteractionProfile& profile, const std::string& path,
                                        ComponentKind preferred);

// The user path a binding path starts with ("/user/hand/left"), or "" when none of the profile's.
std::string user_path_of(const InteractionProfile& profile, const std::string& binding_path);

// Human-readable names for xrGetInputSourceLocalizedName.
std::string localized_user_path(const std::string& user_path);
std::string localized_component(const std::string& component_path);  // e.g. "Menu Click"

}  // namespace pushpull::xrsim
