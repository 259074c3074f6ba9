// Shared helper of the spring energies: |x_j - x_i|^2 for autodiff types.
#pragma once

namespace ipstep {

template <int kDim, typename T>
T SquaredDistance(const T* xi, const T* xj) {
  T d2 = T(0.0);
  for (int k = 0; k < kDim; ++k) {
    const T dk = xj[k] - xi[k];
    d2 += dk * dk;
  }
  return d2;
}

}  // namespace ipstep
