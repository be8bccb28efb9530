#include "Interface.h"
#include "../common/BlockAdd.h"
#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <string>

namespace pushout::interface
{
namespace
{
using Vec = std::array<double, 3>;

Vec cross(const Vec& a, const Vec& b)
{
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
double dot(const Vec& a, const Vec& b)
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
Vec normalized(const Vec& a)
{
  const double n = std::sqrt(dot(a, a));
  return {a[0] / n, a[1] / n, a[2] / n};
}
} // namespace

Interface::Interface(std::vector<std::int32_t> pair_blocks, const std::vector<double>& x,
                     Quadrature quadrature, std::vector<std::unique_ptr<laws::InterfaceLaw>> layers,
                     std::array<double, 3> mirror)
    : _blocks(std::move(pair_blocks)), _num_pairs(x.size() / 12), _mirror(mirror),
      _mirrored(mirror != std::array<double, 3>{0, 0, 0}),
      _n(_num_pairs > 0 ? int(_blocks.size() / (2 * _num_pairs)) : 4), _q(std::move(quadrature)),
      _layers(std::move(layers))
{
  if (_mirrored && std::abs(dot(_mirror, _mirror) - 1) > 1e-12)
    throw std::invalid_argument("Interface: the mirror normal is not a unit vector");
  if (x.size() % 12 != 0 || (_n != 4 && _n != 9) || _blocks.size() != 2 * _n * _num_pairs)
    throw std::invalid_argument("Interface: inconsistent pair arrays");
  const std::size_t nq = _q.weights.size();
  for (const auto& pt : _q.points)
    for (double v : shape(pt, _n))
      _N.push_back(v);
  _Ke.resize(std::size_t(36) * _n * _n);
  _dA.resize(num_points());
  _frame.resize(9 * num_points());
  for (std::size_t p = 0; p < num_pairs(); ++p)
  {
    const double* xp = x.data() + 12 * p;
    for (std::size_t q = 0; q < nq; ++q)
    {
      // Derivatives of the bilinear map at (xi, eta).
      const auto [xi, eta] = _q.points[q];
      const std::array<double, 4> dNx = {-(1 - eta), 1 - eta, -eta, eta};
      const std::array<double, 4> dNe = {-(1 - xi), -xi, 1 - xi, xi};
      Vec gx{0, 0, 0}, ge{0, 0, 0};
      for (int a = 0; a < 4; ++a)
        for (int d = 0; d < 3; ++d)
        {
          gx[d] += dNx[a] * xp[3 * a + d];
          ge[d] += dNe[a] * xp[3 * a + d];
        }
      const Vec nn = cross(gx, ge);
      const double jac = std::sqrt(dot(nn, nn));
      if (!(jac > 0))
        throw std::runtime_error("degenerate interface element");
      const Vec n = normalized(nn);
      // s1: the in-plane direction closest to +z (axial), else along xi.
      Vec s{-n[2] * n[0], -n[2] * n[1], 1 - n[2] * n[2]};
      if (dot(s, s) < 1e-6)
      {
        const double c = dot(gx, n);
        s = {gx[0] - c * n[0], gx[1] - c * n[1], gx[2] - c * n[2]};
      }
      const Vec s1 = normalized(s);
      const Vec s2 = cross(n, s1);
      const std::size_t i = p * nq + q;
      _dA[i] = _q.weights[q] * jac * (_mirrored ? 0.5 : 1.0);
      for (int d = 0; d < 3; ++d)
      {
        _frame[9 * i + d] = n[d];
        _frame[9 * i + 3 + d] = s1[d];
        _frame[9 * i + 6 + d] = s2[d];
      }
    }
  }
  reset();
}

void Interface::set_layers(std::vector<std::unique_ptr<laws::InterfaceLaw>> layers)
{
  _layers = std::move(layers);
  reset();
}

void Interface::reset()
{
  std::vector<int> sizes;
  _softens.clear();
  for (const auto& law : _layers)
  {
    if (law->state_size() > max_state_size)
      throw std::invalid_argument("Interface: a law with more than " +
                                  std::to_string(max_state_size) + " state variables");
    sizes.push_back(law->state_size());
    _softens.push_back(law->softens());
  }
  _state = InterfaceState(num_points(), sizes);
  _t_layer.assign(3 * num_points() * _layers.size(), 0.0);
  _w_last.assign(3 * num_points(), 0.0);
  _t0 = _w0 = _w_last;
  _dissipation_last.assign(2 * num_points(), 0.0);
  _inputs = {};
}

laws::Vec3 Interface::minus_side(const laws::Vec3& v) const
{
  if (!_mirrored)
    return v;
  const double c = 2 * dot(_mirror, v);
  return {v[0] - c * _mirror[0], v[1] - c * _mirror[1], v[2] - c * _mirror[2]};
}

laws::Vec3 Interface::jump(std::span<const double> u, std::size_t p, std::size_t q) const
{
  const std::int32_t* b = _blocks.data() + 2 * _n * p;
  const double* R = _frame.data() + 9 * (p * _q.weights.size() + q);
  const double* N = _N.data() + _n * q;
  Vec w{0, 0, 0};
  for (int a = 0; a < _n; ++a)
  {
    const double* up = &u[3 * b[_n + a]];
    const Vec um = minus_side({u[3 * b[a]], u[3 * b[a] + 1], u[3 * b[a] + 2]});
    for (int d = 0; d < 3; ++d)
      w[d] += N[a] * (up[d] - um[d]);
  }
  return {R[0] * w[0] + R[1] * w[1] + R[2] * w[2], R[3] * w[0] + R[4] * w[1] + R[5] * w[2],
          R[6] * w[0] + R[7] * w[1] + R[8] * w[2]};
}

bool Interface::evaluate(std::size_t i, const laws::Vec3& w, laws::Vec3& t, laws::Mat3& D,
                         laws::Mat3* D_softening)
{
  bool ok = true;
  t = {0, 0, 0};
  D = {};
  std::array<double, 2> dissipated = {0, 0}; // all layers, softening layers
  for (std::size_t l = 0; l < _layers.size(); ++l)
  {
    const laws::LawResult r =
        _layers[l]->update(_state.committed(i, l), w, _state.trial(i, l), _inputs);
    ok = ok && r.status == laws::LawStatus::ok;
    std::copy(r.t.begin(), r.t.end(), _t_layer.begin() + 3 * (i * _layers.size() + l));
    for (int c = 0; c < 3; ++c)
      t[c] += r.t[c];
    for (int c = 0; c < 9; ++c)
      D[c] += r.D[c];
    if (D_softening && _softens[l])
      for (int c = 0; c < 9; ++c)
        (*D_softening)[c] += r.D[c];
    dissipated[0] += r.dissipation;
    if (_softens[l])
      dissipated[1] += r.dissipation;
  }
  std::copy(w.begin(), w.end(), _w_last.begin() + 3 * i);
  _dissipation_last[2 * i] = dissipated[0];
  _dissipation_last[2 * i + 1] = dissipated[1];
  return ok;
}

void Interface::scatter(std::size_t p, std::size_t q, const laws::Vec3& v,
                        std::span<double> f) const
{
  const std::size_t i = p * _q.weights.size() + q;
  const std::int32_t* b = _blocks.data() + 2 * _n * p;
  const double* R = _frame.data() + 9 * i;
  const double* N = _N.data() + _n * q;
  // To the global frame: v_g = R^T v.
  Vec vg{0, 0, 0};
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c)
      vg[c] += R[3 * r + c] * v[r];
  const Vec vm = minus_side(vg);
  for (int a = 0; a < _n; ++a)
    for (int d = 0; d < 3; ++d)
    {
      f[3 * b[a] + d] -= N[a] * vm[d] * _dA[i];      // steel (minus) side
      f[3 * b[_n + a] + d] += N[a] * vg[d] * _dA[i]; // concrete (plus) side
    }
}

bool Interface::assemble(std::span<const double> u, std::span<double> f, Mat A)
{
  const std::size_t nq = _q.weights.size();
  bool ok = true;
  const int n = _n, rows = 6 * n;     // nodes per side, rows of Ke
  std::optional<petsc::BlockAdd> add; // into A
  if (A)
    add.emplace(A);
  for (std::size_t p = 0; p < num_pairs(); ++p)
  {
    const std::int32_t* b = _blocks.data() + 2 * n * p;
    if (A)
      std::fill(_Ke.begin(), _Ke.end(), 0.0);
    for (std::size_t q = 0; q < nq; ++q)
    {
      const std::size_t i = p * nq + q;
      laws::Vec3 t;
      laws::Mat3 D;
      ok = evaluate(i, jump(u, p, q), t, D) && ok;
      scatter(p, q, t, f);
      if (!A)
        continue;
      // To the global frame: D_g = R^T D R.
      const double* R = _frame.data() + 9 * i;
      const double* N = _N.data() + n * q;
      std::array<double, 9> Dg{};
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c)
        {
          double s = 0;
          for (int k = 0; k < 3; ++k)
            for (int m = 0; m < 3; ++m)
              s += R[3 * k + r] * D[3 * k + m] * R[3 * m + c];
          Dg[3 * r + c] = s;
        }
      // Blocks of the sides (0 steel or minus, 1 concrete or plus): M D_g M,
      // M D_g, D_g M, D_g, with M the mirror of a mirror set (else I).
      std::array<std::array<std::array<double, 9>, 2>, 2> Dside;
      for (int c = 0; c < 3; ++c)
      {
        const Vec col = minus_side({Dg[c], Dg[3 + c], Dg[6 + c]}); // M D_g, column c
        for (int r = 0; r < 3; ++r)
        {
          Dside[1][1][3 * r + c] = Dg[3 * r + c];
          Dside[0][1][3 * r + c] = col[r];
        }
      }
      for (int r = 0; r < 3; ++r)
      {
        const Vec row = minus_side({Dg[3 * r], Dg[3 * r + 1], Dg[3 * r + 2]}); // D_g M (M = M^T)
        const Vec row_m = minus_side(
            {Dside[0][1][3 * r], Dside[0][1][3 * r + 1], Dside[0][1][3 * r + 2]}); // M D_g M
        for (int c = 0; c < 3; ++c)
        {
          Dside[1][0][3 * r + c] = row[c];
          Dside[0][0][3 * r + c] = row_m[c];
        }
      }
      // Node a of side sa against node b of side sb: sign + on the same
      // side, - across.
      for (int sa = 0; sa < 2; ++sa)
        for (int a = 0; a < n; ++a)
          for (int sb = 0; sb < 2; ++sb)
            for (int bb = 0; bb < n; ++bb)
            {
              const double c = (sa == sb ? 1.0 : -1.0) * N[a] * N[bb] * _dA[i];
              if (c == 0.0)
                continue; // nodal quadrature: other nodes
              const int row = 3 * (n * sa + a), col = 3 * (n * sb + bb);
              const std::array<double, 9>& Db = Dside[sa][sb];
              for (int r = 0; r < 3; ++r)
                for (int k = 0; k < 3; ++k)
                  _Ke[rows * (row + r) + col + k] += c * Db[3 * r + k];
            }
    }
    if (add)
    {
      const std::span<const std::int32_t> nodes(b, std::size_t(2 * n));
      (*add)(nodes, nodes, _Ke);
    }
  }
  return ok;
}

void Interface::commit()
{
  _state.commit();
  _w0 = _w_last;
  for (std::size_t i = 0; i < num_points(); ++i)
    softening_traction(i, _t0.data() + 3 * i);
}

void Interface::softening_traction(std::size_t i, double* t) const
{
  for (int c = 0; c < 3; ++c)
  {
    t[c] = 0;
    for (std::size_t l = 0; l < _layers.size(); ++l)
      if (_softens[l])
        t[c] += layer_traction(i, l)[c];
  }
}

bool Interface::energy_release(std::span<const double> u, std::span<double> gradient, double& G)
{
  const std::size_t nq = _q.weights.size();
  bool ok = true;
  G = 0;
  for (std::size_t p = 0; p < num_pairs(); ++p)
    for (std::size_t q = 0; q < nq; ++q)
    {
      const std::size_t i = p * nq + q;
      const laws::Vec3 w = jump(u, p, q);
      laws::Vec3 t_all, t;
      laws::Mat3 D_all, D{};
      ok = evaluate(i, w, t_all, D_all, &D) && ok;
      softening_traction(i, t.data());
      const double* t0 = _t0.data() + 3 * i;
      const double* w0 = _w0.data() + 3 * i;
      double change = 0, size = 0;
      for (int c = 0; c < 3; ++c)
      {
        G += 0.5 * (t0[c] * w[c] - t[c] * w0[c]) * _dA[i];
        change = std::max(change, std::abs(w[c] - w0[c]));
        size = std::max(size, std::abs(w0[c]));
      }
      // Where the jump is still the committed one, a damage law's tangent is
      // the secant (no loading yet) and dG/dw would vanish: take the loading
      // tangent, from the laws just beyond w0 along w0 (the trial state of
      // this probe is thrown away).
      if (change <= loading_probe * size && size > 0)
      {
        const laws::Vec3 w_probe = {w[0] * (1 + loading_probe), w[1] * (1 + loading_probe),
                                    w[2] * (1 + loading_probe)};
        std::array<double, max_state_size> scratch;
        D = {};
        for (std::size_t l = 0; l < _layers.size(); ++l)
        {
          if (!_softens[l])
            continue;
          const laws::LawResult r = _layers[l]->update(
              _state.committed(i, l), w_probe,
              std::span<double>(scratch.data(), std::size_t(_state.size(l))), _inputs);
          for (int c = 0; c < 9; ++c)
            D[c] += r.D[c];
        }
      }
      // dG/dw = 1/2 (t0 - D^T w0)
      laws::Vec3 g;
      for (int c = 0; c < 3; ++c)
        g[c] = 0.5 * (t0[c] - (D[c] * w0[0] + D[3 + c] * w0[1] + D[6 + c] * w0[2]));
      scatter(p, q, g, gradient);
    }
  return ok;
}

double Interface::dissipation(bool softening_only) const
{
  double d = 0;
  for (std::size_t i = 0; i < num_points(); ++i)
    d += _dissipation_last[2 * i + (softening_only ? 1 : 0)] * _dA[i];
  return d;
}

double Interface::fracture_energy() const
{
  double per_area = 0;
  for (const auto& law : _layers)
    per_area += law->fracture_energy();
  return per_area * area();
}

PointOutput Interface::point_output(std::span<const double> u, std::size_t p, std::size_t q) const
{
  const std::size_t i = p * _q.weights.size() + q;
  PointOutput out;
  out.w = jump(u, p, q);
  out.t = {0, 0, 0};
  for (std::size_t l = 0; l < _layers.size(); ++l)
  {
    for (int c = 0; c < 3; ++c)
      out.t[c] += layer_traction(i, l)[c];
    out.slip.push_back(_layers[l]->slip(_state.trial(i, l)));
    out.damage.push_back(_layers[l]->damage(_state.trial(i, l)));
  }
  return out;
}

std::vector<double> Interface::normal_force() const
{
  std::vector<double> force(_layers.size(), 0.0);
  for (std::size_t i = 0; i < num_points(); ++i)
    for (std::size_t l = 0; l < _layers.size(); ++l)
      force[l] += layer_traction(i, l)[0] * _dA[i];
  return force;
}

Interface::ShearSpread Interface::shear_spread() const
{
  ShearSpread s;
  for (std::size_t i = 0; i < num_points(); ++i)
  {
    double t = 0;
    for (std::size_t l = 0; l < _layers.size(); ++l)
      t += layer_traction(i, l)[1];
    s.integral += t * _dA[i];
    s.integral_of_magnitude += std::abs(t) * _dA[i];
    s.integral_of_square += t * t * _dA[i];
    s.min = std::min(s.min, t);
    s.max = std::max(s.max, t);
  }
  return s;
}

std::array<double, 2> Interface::damage_of(std::size_t layer) const
{
  std::array<double, 2> d = {0, 0};
  for (std::size_t i = 0; i < num_points(); ++i)
  {
    const double D = _layers[layer]->damage(_state.trial(i, layer));
    d[0] += D * _dA[i];
    d[1] = std::max(d[1], D);
  }
  return d;
}

laws::Vec3 Interface::resultant() const
{
  laws::Vec3 force{0, 0, 0};
  for (std::size_t i = 0; i < num_points(); ++i)
  {
    const double* R = _frame.data() + 9 * i;
    for (std::size_t l = 0; l < _layers.size(); ++l)
    {
      const double* t = layer_traction(i, l);
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c)
          force[c] += R[3 * r + c] * t[r] * _dA[i];
    }
  }
  return force;
}

void Interface::add_jump_functional(const laws::Vec3& v, std::span<double> a) const
{
  for (std::size_t p = 0; p < num_pairs(); ++p)
    for (std::size_t q = 0; q < _q.weights.size(); ++q)
      scatter(p, q, v, a); // w . v
}

std::array<double, 2> Interface::opening_near(std::span<const double> u,
                                              std::span<const std::int32_t> plus_blocks) const
{
  std::array<double, 2> sum = {0, 0};
  const std::size_t nq = _q.weights.size();
  for (std::size_t p = 0; p < _num_pairs; ++p)
  {
    const std::int32_t* plus = _blocks.data() + 2 * _n * p + _n;
    for (std::size_t q = 0; q < nq; ++q)
    {
      const double* N = _N.data() + _n * q;
      double weight = 0; // of the given nodes at point q
      for (int a = 0; a < _n; ++a)
        if (std::binary_search(plus_blocks.begin(), plus_blocks.end(), plus[a]))
          weight += N[a];
      if (weight > 0.5)
      {
        const double dA = _dA[p * nq + q];
        sum[0] += jump(u, p, q)[0] * dA;
        sum[1] += dA;
      }
    }
  }
  return sum;
}

double Interface::area() const
{
  double a = 0;
  for (double d : _dA)
    a += d;
  return a;
}
} // namespace pushout::interface
