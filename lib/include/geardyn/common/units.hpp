/// @file
/// @brief Unit conversions used only at the input/output boundary (geardyn is SI inside).
#pragma once

#include <numbers>

namespace geardyn {

inline constexpr double kPi = std::numbers::pi;

/// Degrees → radians.
constexpr double DegToRad(double deg) { return deg * kPi / 180.0; }
/// Radians → degrees.
constexpr double RadToDeg(double rad) { return rad * 180.0 / kPi; }
/// Revolutions per minute → rad/s.
constexpr double RpmToRadPerSec(double rpm) { return rpm * 2.0 * kPi / 60.0; }
/// rad/s → revolutions per minute.
constexpr double RadPerSecToRpm(double w) { return w * 60.0 / (2.0 * kPi); }

}  // namespace geardyn
