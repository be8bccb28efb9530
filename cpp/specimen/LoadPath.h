// A piecewise-linear path of a prescribed displacement [mm] through the
// vertices v_0, v_1, ..., v_m (the single joint's loading.shear_path, the
// push-out's loading.push_path), each segment in `per_segment` nominal
// steps: the load parameter s in [0, m per_segment] gives
//   value(s) = v_j + (s / per_segment - j) (v_{j+1} - v_j),
//   j = floor(s / per_segment) (the last segment for s at the end),
// and the path length travelled to s (the pseudo-time of viscous laws).
// A segment can be ended early (end_segment: an unloading push that stops
// where the force reaches zero); the path goes on from there, past the
// unloading segments right after it, which would pull.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace pushout::specimen
{
/// The checks of a path key (`key`: loading.push_path or
/// loading.shear_path) beyond its type: a segment at least, from 0, and at
/// most steps_per_segment's bound of steps on all its segments together.
/// Throws SceneError naming the key.
void check_load_path(const std::string& key, const std::vector<double>& path,
                     std::int64_t per_segment);

class LoadPath
{
public:
  LoadPath() = default;
  /// Vertices as check_load_path accepts them (or none: no path).
  LoadPath(std::vector<double> vertices, int per_segment)
      : _v(std::move(vertices)), _per_segment(per_segment)
  {
  }

  bool empty() const { return _v.empty(); }
  std::size_t segments() const { return _v.empty() ? 0 : _v.size() - 1; }
  int steps() const { return int(segments()) * _per_segment; }

  /// The segment of load parameter s (the segment it ends, at a vertex).
  std::size_t segment_at(double s) const
  {
    const double t = std::max(s, 0.0) / _per_segment;
    return std::min(std::size_t(std::ceil(t)) - (t > 0 ? 1 : 0), segments() - 1);
  }
  /// The segment of nominal step k (1-based: from s = k - 1 to k).
  std::size_t segment_of_step(int k) const { return std::size_t(k - 1) / _per_segment; }
  /// Whether segment j moves the value down.
  bool decreasing(std::size_t j) const { return _v[j + 1] < _v[j]; }

  /// The value at load parameter s [mm].
  double value(double s) const
  {
    const std::size_t j = segment_at(s);
    const double f = s / _per_segment - double(j);
    return _v[j] + f * (_v[j + 1] - _v[j]);
  }

  /// The path length from s = 0 to s [mm].
  double length_to(double s) const
  {
    const std::size_t j = segment_at(s);
    double length = 0;
    for (std::size_t i = 0; i < j; ++i)
      length += std::abs(_v[i + 1] - _v[i]);
    return length + std::abs(value(s) - _v[j]);
  }

  /// Ends segment j at load parameter s inside it: its end vertex becomes
  /// value(s), and so does the end of each segment right after it that
  /// ends at or below that value (an unloading on to it would pull), so
  /// that the path goes on from value(s). Returns the load parameter where
  /// it goes on: the end of the last segment so ended.
  double end_segment(std::size_t j, double s)
  {
    const double end = value(s);
    _v[j + 1] = end;
    for (; j + 2 < _v.size() && _v[j + 2] <= end; ++j)
      _v[j + 2] = end;
    return double((j + 1) * std::size_t(_per_segment));
  }

private:
  std::vector<double> _v;
  int _per_segment = 1;
};
} // namespace pushout::specimen
