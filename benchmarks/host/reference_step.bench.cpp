// What this machine does with the step of the engine's USL benchmark when it is written by
// hand, without the library: the "tight hand-written loop" (issue 17), kept so the
// library's figures can be read against it in the same minutes. The same block as
// step/linear/FusedUSL (120 x 35 cells of 10 mm filled with 2 x 2 particles, 16,800, on a
// fixed floor between roller walls, linear elastic corn, FLIP 0.99), the same physics per
// particle (gather of velocity, acceleration and velocity gradient; blended velocity,
// position, F, volume, Jaumann rotation and elastic update of the stress with sigma_zz,
// accumulated strain, the velocity gradient kept; scatter of mass, momentum and forces at the
// new position), one pass over the particles per step and a node pass, with none of the
// library's checks, bookkeeping or policies.
//   reference_step/records: particle fields as the library keeps them (a record per particle
//     and field: x[p] = (x, y), F[p] = 4 doubles, ...), four particles per pack built from them.
//   reference_step/by_component: every component its own array (x, y, F00, ...), so packs load
//     whole.
//   build/release/benchmarks/cosmpm_bench_host --benchmark_filter=reference_step
#include <benchmark/benchmark.h>

#include <cmath>
#include <vector>

#if defined(__GNUC__) || defined(__clang__)
namespace {

typedef double v4 __attribute__((vector_size(32)));
constexpr int nodes_x = 121, nodes_y = 51, node_count = nodes_x * nodes_y;
constexpr int particles_x = 240, particles_y = 70, particle_count = particles_x * particles_y;
constexpr double cell = 0.01, inverse_cell = 100.0;

inline v4 load4(const double* p) {
  v4 r;
  __builtin_memcpy(&r, p, sizeof(r));
  return r;
}
inline void store4(double* p, v4 a) {
  __builtin_memcpy(p, &a, sizeof(a));
}

// A particle field of `components` doubles, by record (the library's layout) or by component.
template <bool by_component>
struct Field {
  std::vector<double> data;
  int components;
  Field(int c, double value)
      : data(static_cast<std::size_t>(particle_count * c), value), components(c) {}
  double& operator()(int p, int c) {
    return data[static_cast<std::size_t>(by_component ? c * particle_count + p
                                                      : p * components + c)];
  }
  v4 pack(int p, int c) {
    if constexpr (by_component) {
      return load4(&(*this)(p, c));
    } else {
      return v4{(*this)(p, c), (*this)(p + 1, c), (*this)(p + 2, c), (*this)(p + 3, c)};
    }
  }
  void set(int p, int c, v4 a) {
    if constexpr (by_component) {
      store4(&(*this)(p, c), a);
    } else {
      for (int l = 0; l < 4; ++l) (*this)(p + l, c) = a[l];
    }
  }
};

template <bool by_component>
void reference_step(benchmark::State& state) {
  using F = Field<by_component>;
  F x(2, 0.0), v(2, 0.0), deformation(4, 0.0), volume(1, cell * cell / 4),
      initial_volume(1, cell * cell / 4), mass(1, 778.0 * cell * cell / 4), stress(4, 0.0),
      strain(4, 0.0), gradient(4, 0.0), in_cells(2, 0.0);
  for (int j = 0, p = 0; j < particles_y; ++j) {
    for (int i = 0; i < particles_x; ++i, ++p) {
      x(p, 0) = (i + 0.5) * cell / 2;
      x(p, 1) = (j + 0.5) * cell / 2;
      deformation(p, 0) = deformation(p, 3) = 1.0;
      in_cells(p, 0) = x(p, 0) * inverse_cell;
      in_cells(p, 1) = x(p, 1) * inverse_cell;
    }
  }
  const double youngs = 2.76e6, poisson = 0.2;
  const double shear = youngs / (2 * (1 + poisson));
  const double lambda = youngs * poisson / ((1 + poisson) * (1 - 2 * poisson));
  const double dt = 0.5 * cell / std::sqrt((lambda + 2 * shear) / 778.0);
  const double flip = 0.99, gravity = -9.81;
  std::vector<double> scatter_records(5 * node_count + 8), gather_records(4 * node_count + 8);
  double* const scattered = scatter_records.data();
  double* const gathered = gather_records.data();
  // Mass, momentum and force of particle p to its four nodes, a node's record in registers.
  const auto scatter = [&](int p) {
    const double cx = in_cells(p, 0), cy = in_cells(p, 1);
    const int i = static_cast<int>(cx), j = static_cast<int>(cy);
    const double fx = cx - i, fy = cy - j;
    const double m = mass(p, 0), vol = volume(p, 0);
    const v4 weighted = {m, m * v(p, 0), m * v(p, 1), 0.0};
    const double weighted_y = m * gravity;
    const v4 by_dy = {0, 0, 0, -vol * stress(p, 3)};
    const double by_dy_y = -vol * stress(p, 1);
    const v4 by_dx = {0, 0, 0, -vol * stress(p, 0)};
    const double by_dx_y = -vol * stress(p, 3);
    const double ny[2] = {1 - fy, fy}, dny[2] = {-inverse_cell, inverse_cell};
    for (int b = 0; b < 2; ++b) {
      const v4 a = ny[b] * weighted + dny[b] * by_dy;
      const double a_y = ny[b] * weighted_y + dny[b] * by_dy_y;
      const v4 c = ny[b] * by_dx;
      const double c_y = ny[b] * by_dx_y;
      double* const r = scattered + 5 * ((j + b) * nodes_x + i);
      store4(r, load4(r) + (1 - fx) * a - inverse_cell * c);
      r[4] += (1 - fx) * a_y - inverse_cell * c_y;
      store4(r + 5, load4(r + 5) + fx * a + inverse_cell * c);
      r[9] += fx * a_y + inverse_cell * c_y;
    }
  };
  for (int p = 0; p < particle_count; ++p) scatter(p);
  for (auto _ : state) {
    for (int k = 0; k < node_count; ++k) {
      double* const r = scattered + 5 * k;
      double* const g = gathered + 4 * k;
      if (r[0] > 0) {
        const double inverse_mass = 1 / r[0];
        double vx = r[1] * inverse_mass, vy = r[2] * inverse_mass;
        double ax = r[3] * inverse_mass, ay = r[4] * inverse_mass;
        const int i = k % nodes_x, j = k / nodes_x;
        if (j == 0) vx = vy = ax = ay = 0;            // fixed floor
        if (i == 0 || i == nodes_x - 1) vx = ax = 0;  // roller walls
        g[0] = vx + ax * dt;
        g[1] = vy + ay * dt;
        g[2] = ax;
        g[3] = ay;
      } else {
        g[0] = g[1] = g[2] = g[3] = 0;
      }
      for (int c = 0; c < 5; ++c) r[c] = 0;
    }
    for (int p = 0; p < particle_count; p += 4) {
      // Gather lane by lane, a node's record in one register, then transposed.
      v4 value[4], d_dx[4], d_dy[4];
      for (int l = 0; l < 4; ++l) {
        const double cx = in_cells(p + l, 0), cy = in_cells(p + l, 1);
        const int i = static_cast<int>(cx), j = static_cast<int>(cy);
        const double fx = cx - i, fy = cy - j;
        const double* const g0 = gathered + 4 * (j * nodes_x + i);
        const double* const g1 = g0 + 4 * nodes_x;
        const v4 r0 = (1 - fx) * load4(g0) + fx * load4(g0 + 4);
        const v4 r1 = (1 - fx) * load4(g1) + fx * load4(g1 + 4);
        const v4 x0 = inverse_cell * (load4(g0 + 4) - load4(g0));
        const v4 x1 = inverse_cell * (load4(g1 + 4) - load4(g1));
        value[l] = (1 - fy) * r0 + fy * r1;
        d_dx[l] = (1 - fy) * x0 + fy * x1;
        d_dy[l] = inverse_cell * (r1 - r0);
      }
      const auto lanes = [](const v4* a, int c) { return v4{a[0][c], a[1][c], a[2][c], a[3][c]}; };
      const v4 vx_grid = lanes(value, 0), vy_grid = lanes(value, 1);
      const v4 ax_grid = lanes(value, 2), ay_grid = lanes(value, 3);
      const v4 l00 = lanes(d_dx, 0), l10 = lanes(d_dx, 1), l01 = lanes(d_dy, 0),
               l11 = lanes(d_dy, 1);
      const v4 vx = flip * (v.pack(p, 0) + dt * ax_grid) + (1 - flip) * vx_grid;
      const v4 vy = flip * (v.pack(p, 1) + dt * ay_grid) + (1 - flip) * vy_grid;
      v.set(p, 0, vx);
      v.set(p, 1, vy);
      const v4 x0 = x.pack(p, 0) + dt * vx_grid, x1 = x.pack(p, 1) + dt * vy_grid;
      x.set(p, 0, x0);
      x.set(p, 1, x1);
      in_cells.set(p, 0, x0 * inverse_cell);
      in_cells.set(p, 1, x1 * inverse_cell);
      gradient.set(p, 0, l00);
      gradient.set(p, 1, l10);
      gradient.set(p, 2, l01);
      gradient.set(p, 3, l11);
      const v4 a00 = 1 + l00 * dt, a01 = l01 * dt, a10 = l10 * dt, a11 = 1 + l11 * dt;
      const v4 f00 = deformation.pack(p, 0), f10 = deformation.pack(p, 1);
      const v4 f01 = deformation.pack(p, 2), f11 = deformation.pack(p, 3);
      const v4 n00 = a00 * f00 + a01 * f10, n01 = a00 * f01 + a01 * f11;
      const v4 n10 = a10 * f00 + a11 * f10, n11 = a10 * f01 + a11 * f11;
      deformation.set(p, 0, n00);
      deformation.set(p, 1, n10);
      deformation.set(p, 2, n01);
      deformation.set(p, 3, n11);
      volume.set(p, 0, initial_volume.pack(p, 0) * (n00 * n11 - n01 * n10));
      const v4 spin = 0.5 * (l01 - l10) * dt;
      const v4 sxx = stress.pack(p, 0), syy = stress.pack(p, 1), sxy = stress.pack(p, 3);
      const v4 dxx = l00 * dt, dyy = l11 * dt, dxy = 0.5 * (l01 + l10) * dt, trace = dxx + dyy;
      stress.set(p, 0, sxx + 2 * spin * sxy + lambda * trace + 2 * shear * dxx);
      stress.set(p, 1, syy - 2 * spin * sxy + lambda * trace + 2 * shear * dyy);
      stress.set(p, 2, stress.pack(p, 2) + lambda * trace);
      stress.set(p, 3, sxy + spin * (syy - sxx) + 2 * shear * dxy);
      strain.set(p, 0, strain.pack(p, 0) + dxx);
      strain.set(p, 1, strain.pack(p, 1) + dyy);
      strain.set(p, 3, strain.pack(p, 3) + dxy);
      for (int l = 0; l < 4; ++l) scatter(p + l);
    }
    benchmark::DoNotOptimize(scattered);
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() * particle_count);
  state.counters["particles"] = particle_count;
}

}  // namespace

BENCHMARK_TEMPLATE(reference_step, false)->Name("reference_step/records")->UseRealTime();
BENCHMARK_TEMPLATE(reference_step, true)->Name("reference_step/by_component")->UseRealTime();
#endif
