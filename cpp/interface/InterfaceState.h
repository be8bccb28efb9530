// History variables of all interface layers at all quadrature points.
//
// Layout (contiguous): [pair][quadrature point][layer variables], the layers'
// variables concatenated in scene order; `offset(layer)` locates a layer.
// Two copies (MGIS-style): `committed` is the state at the end of the last
// converged load step; `trial` is written by every residual evaluation from
// `committed` and the current jump. commit() after a converged step;
// revert() before retrying a step that was cut back.
#pragma once

#include <span>
#include <vector>

namespace pushout::interface
{
class InterfaceState
{
public:
  InterfaceState() = default;
  InterfaceState(std::size_t num_points, const std::vector<int>& layer_sizes)
  {
    _offsets.push_back(0);
    for (int s : layer_sizes)
      _offsets.push_back(_offsets.back() + s);
    _committed.assign(num_points * stride(), 0.0);
    _trial = _committed;
  }

  int stride() const { return _offsets.back(); }
  int offset(std::size_t layer) const { return _offsets[layer]; }
  int size(std::size_t layer) const { return _offsets[layer + 1] - _offsets[layer]; }

  std::span<const double> committed(std::size_t point, std::size_t layer) const
  {
    return {_committed.data() + point * stride() + offset(layer), std::size_t(size(layer))};
  }
  std::span<double> trial(std::size_t point, std::size_t layer)
  {
    return {_trial.data() + point * stride() + offset(layer), std::size_t(size(layer))};
  }
  std::span<const double> trial(std::size_t point, std::size_t layer) const
  {
    return {_trial.data() + point * stride() + offset(layer), std::size_t(size(layer))};
  }

  void commit() { _committed = _trial; }
  void revert() { _trial = _committed; }

private:
  std::vector<int> _offsets;
  std::vector<double> _committed, _trial;
};
} // namespace pushout::interface
