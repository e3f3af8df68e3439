#pragma once
// A plain 2D vector: the only geometric type the solver needs.
#include <cmath>
#include <numbers>

namespace vdec {

struct Vec2 {
  double x = 0.0;
  double y = 0.0;
};

constexpr Vec2 operator+(Vec2 a, Vec2 b) { return {a.x + b.x, a.y + b.y}; }
constexpr Vec2 operator-(Vec2 a, Vec2 b) { return {a.x - b.x, a.y - b.y}; }
constexpr Vec2 operator-(Vec2 a) { return {-a.x, -a.y}; }
constexpr Vec2 operator*(double s, Vec2 a) { return {s * a.x, s * a.y}; }
constexpr Vec2 operator*(Vec2 a, double s) { return {s * a.x, s * a.y}; }
constexpr Vec2& operator+=(Vec2& a, Vec2 b) { a.x += b.x; a.y += b.y; return a; }
constexpr Vec2& operator-=(Vec2& a, Vec2 b) { a.x -= b.x; a.y -= b.y; return a; }
constexpr double dot(Vec2 a, Vec2 b) { return a.x * b.x + a.y * b.y; }
// z-component of the 3D cross product: positive when b lies counter-clockwise of a.
constexpr double cross(Vec2 a, Vec2 b) { return a.x * b.y - a.y * b.x; }
// a rotated +90 degrees.
constexpr Vec2 perp(Vec2 a) { return {-a.y, a.x}; }
// Plain square root: coordinates and forces here are far from overflow, and std::hypot costs
// several times more in the contact loop.
inline double norm(Vec2 a) { return std::sqrt(a.x * a.x + a.y * a.y); }
inline Vec2 normalized(Vec2 a) { return (1.0 / norm(a)) * a; }
inline Vec2 rotated(Vec2 a, double c, double s) { return {c * a.x - s * a.y, s * a.x + c * a.y}; }
inline double radians(double degrees) { return degrees * std::numbers::pi / 180.0; }

}  // namespace vdec
