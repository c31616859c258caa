/// @file
/// @brief RunArnoldiLargestMagnitude: ARPACK dnaupd/dneupd in regular mode (bmat = 'I', mode 1,
/// which = "LM"), after ARPACK's example driver dndrv1 (ARPACK Users' Guide, Lehoucq, Sorensen &
/// Yang, SIAM 1998, §2.3 and the argument lists in arpack-ng's SRC/dnaupd.f, SRC/dneupd.f).
#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <cstddef>
#include <mutex>
#include <sstream>
#include <vector>

#include "geardyn/common/check.hpp"
#include "geardyn/numerics/nonsymmetric_eigen.hpp"

#if defined(GEARDYN_WITH_ARPACK)
#include "numerics/arpack_fortran.hpp"
#endif

namespace geardyn {

ArnoldiOutcome RunArnoldiLargestMagnitude(const std::function<void(const double*, double*)>& apply,
                                          int n, int nev, int ncv, double tol, int max_iterations) {
  ArnoldiOutcome out;
#if !defined(GEARDYN_WITH_ARPACK)
  (void)apply, (void)n, (void)nev, (void)ncv, (void)tol, (void)max_iterations;
  out.message = "ARPACK unavailable (built with GEARDYN_WITH_ARPACK=OFF)";
  return out;
#else
  GEARDYN_DEMAND(nev >= 1 && nev + 2 <= ncv && ncv <= n);
  const std::lock_guard<std::mutex> lock(internal::ArpackMutex());
  const char bmat = 'I';
  const char which[2] = {'L', 'M'};
  // Fixed, generic start vector (ARPACK's own random start changes from call to call).
  VectorX resid(n);
  for (int i = 0; i < n; ++i) resid[i] = 1.0 + 0.5 * std::sin(0.7 * i + 0.3);
  MatrixX v(n, ncv);
  const int ldv = n;
  VectorX workd(3 * static_cast<Eigen::Index>(n));
  const int lworkl = 3 * ncv * ncv + 6 * ncv;
  VectorX workl(lworkl);
  std::array<int, 11> iparam{};
  iparam[0] = 1;  // exact shifts
  iparam[2] = max_iterations;
  iparam[3] = 1;  // block size
  iparam[6] = 1;  // mode 1: OP = A, B = I
  std::array<int, 14> ipntr{};
  int ido = 0, info = 1;  // info = 1: resid is the start vector
  const auto at = [&workd](int pointer) { return workd.data() + (pointer - 1); };
  while (true) {
    dnaupd_(&ido, &bmat, &n, which, &nev, &tol, resid.data(), &ncv, v.data(), &ldv, iparam.data(),
            ipntr.data(), workd.data(), workl.data(), &lworkl, &info, 1, 2);
    if (ido == -1 || ido == 1) {
      apply(at(ipntr[0]), at(ipntr[1]));
      ++out.applications;
    } else {
      break;  // 99: done (ido 2, 3 do not occur in mode 1 with exact shifts)
    }
  }
  out.info = info;
  out.iterations = iparam[2];
  out.num_converged = iparam[4];
  std::ostringstream why;
  if (info < 0) {
    why << "ARPACK dnaupd error info = " << info;
    out.message = why.str();
    return out;
  }
  if (out.num_converged <= 0) {
    why << "ARPACK dnaupd: no Ritz value converged (info = " << info << ", " << out.iterations
        << " restarts)";
    out.message = why.str();
    return out;
  }
  const int rvec = 1;
  const char howmny = 'A';
  std::vector<int> select(static_cast<std::size_t>(ncv), 0);
  VectorX dr(nev + 1), di(nev + 1), workev(3 * ncv);
  MatrixX z(n, nev + 1);
  const int ldz = n;
  const double sigmar = 0.0, sigmai = 0.0;
  int eupd_info = 0;
  dneupd_(&rvec, &howmny, select.data(), dr.data(), di.data(), z.data(), &ldz, &sigmar, &sigmai,
          workev.data(), &bmat, &n, which, &nev, &tol, resid.data(), &ncv, v.data(), &ldv,
          iparam.data(), ipntr.data(), workd.data(), workl.data(), &lworkl, &eupd_info, 1, 1, 2);
  out.eupd_info = eupd_info;
  if (eupd_info != 0) {
    why << "ARPACK dneupd error info = " << eupd_info;
    out.message = why.str();
    return out;
  }
  const int nconv = std::min(iparam[4], nev + 1);
  out.num_converged = std::min(nconv, nev);
  // Z(:, j) ± i Z(:, j+1) for a conjugate pair dr(j) ± i di(j) (dneupd.f).
  std::vector<std::complex<double> > values;
  std::vector<VectorXc> vectors;
  for (int j = 0; j < nconv; ++j) {
    if (di[j] == 0.0) {
      values.emplace_back(dr[j], 0.0);
      vectors.push_back(z.col(j).cast<std::complex<double> >());
    } else if (j + 1 < nconv + 1 && j + 1 < z.cols()) {
      VectorXc x = z.col(j).cast<std::complex<double> >() +
                   std::complex<double>(0.0, 1.0) * z.col(j + 1).cast<std::complex<double> >();
      values.emplace_back(dr[j], di[j]);
      vectors.push_back(x);
      if (j + 1 < nconv) {
        values.emplace_back(dr[j], -di[j]);
        vectors.push_back(x.conjugate());
      }
      ++j;
    }
  }
  out.values.resize(static_cast<Eigen::Index>(values.size()));
  out.vectors.resize(n, static_cast<Eigen::Index>(values.size()));
  for (std::size_t k = 0; k < values.size(); ++k) {
    out.values[static_cast<Eigen::Index>(k)] = values[k];
    out.vectors.col(static_cast<Eigen::Index>(k)) = vectors[k] / vectors[k].norm();
  }
  out.ok = true;
  if (info == 1) {
    why << "ARPACK dnaupd reached arpack_max_iterations = " << max_iterations << " with "
        << iparam[4] << " of " << nev << " Ritz values converged (info = 1)";
  } else if (info == 3) {
    why << "ARPACK dnaupd could not apply shifts during a restart (info = 3); increase "
           "arpack_ncv (ncv = "
        << ncv << ")";
  } else if (iparam[4] < nev) {
    why << "ARPACK: " << iparam[4] << " of " << nev << " Ritz values converged";
  }
  out.message = why.str();
  return out;
#endif
}

}  // namespace geardyn
