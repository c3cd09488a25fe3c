#pragma once
namespace ricci {
/// Library version, "major.minor.patch".
const char* version();
}  // namespace ricci
