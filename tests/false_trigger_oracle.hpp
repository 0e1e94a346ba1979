#pragma once
// scipy's side of the false-trigger tests (SENSOR-SPEC §11): Python source that defines, for one
// receiver (threshold T, σ_1km S, background B, busy intervals), the intensity λ(r) of the Poisson
// process of false triggers, its integral Λ(r) by scipy's adaptive quadrature, and `first_cdf`,
// the distribution of the first trigger's range given one below R, from a fine cumulative
// trapezoid of λ — independent of owsim's closed form and of its inversion.
#include <string>
#include <utility>
#include <vector>

#include "python_oracle.hpp"

namespace owsim::test {

inline std::string false_trigger_oracle_python(
    double threshold, double noise_at_1km, double background, double gate_m,
    const std::vector<std::pair<double, double>>& busy = {}) {
  std::string busy_list = "[";
  for (const auto& [begin, end] : busy) {
    busy_list += "(" + python_number(begin) + "," + python_number(end) + "),";
  }
  busy_list += "]";
  return "import numpy as np\nfrom scipy.integrate import quad, cumulative_trapezoid\n"
         "from scipy import stats\n"
         "c = 299792500.0 / 1.0003\ntau = 5e-9\ngate = " +
         python_number(gate_m) + "\nT = " + python_number(threshold) +
         "\nS = " + python_number(noise_at_1km) + "\nB = " + python_number(background) +
         "\nbusy = " + busy_list +
         "\n"
         "def lam(x):\n"
         "    x = np.asarray(x, dtype=float)\n"
         "    with np.errstate(divide='ignore', over='ignore'):\n"
         "        s = S * (x / 1000.0) ** 2 * np.sqrt(1 + B)\n"
         "        v = np.where(x > 0, (2 / c) * np.exp(-T ** 2 / (2 * s * s)) / (2 * np.sqrt(3) * "
         "tau), 0.0)\n"
         "    for a, e in busy: v = np.where((x >= a) & (x < e), 0.0, v)\n"
         "    return v\n"
         "cuts = sorted({p for ab in busy for p in ab if 0 < p < gate})\n"
         "def Lam(r):\n"
         "    edges = [0.0] + [p for p in cuts if p < r] + [r]\n"
         "    return sum(quad(lambda x: float(lam(x)), a, b, limit=500, epsabs=0, "
         "epsrel=1e-11)[0]\n"
         "               for a, b in zip(edges[:-1], edges[1:]) if b > a)\n"
         "grid = np.linspace(0.0, gate, 400001)\n"
         "Lgrid = cumulative_trapezoid(lam(grid), grid, initial=0.0)\n"
         "def first_cdf(R):\n"
         "    top = np.interp(R, grid, Lgrid)\n"
         "    return lambda r: (1 - np.exp(-np.interp(np.minimum(r, R), grid, Lgrid))) / (1 - "
         "np.exp(-top))\n";
}

}  // namespace owsim::test
