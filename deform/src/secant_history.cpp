#include "secant_history.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

namespace pushpull::deform::detail {
namespace {

// Entries per chunk: a multiple of 3 (chunks start on a vertex) small enough that the chunk's new pair, f and
// one stored column's chunk stay in the first-level caches while every stored column passes by.
constexpr Eigen::Index kChunk = 3 * 1024;
// Sums per stored column: dF_new.dF_k, dF_new.dG_k, dF_k.dG_new, dG_new.dG_k, dF_k.f.
constexpr int kSums = 5;

// Largest squared norm over consecutive triples of v[0, length) (a trailing partial triple counts too).
double largest_triple(const double* v, Eigen::Index length) {
  double largest = 0.0;
  Eigen::Index i = 0;
  for (; i + 3 <= length; i += 3)
    largest = std::max(largest, v[i] * v[i] + v[i + 1] * v[i + 1] + v[i + 2] * v[i + 2]);
  double rest = 0.0;
  for (; i < length; ++i) rest += v[i] * v[i];
  return std::max(largest, rest);
}

}  // namespace

SecantHistory::SecantHistory(int window, Eigen::Index dimension)
    : window_(std::max(window, 1)),
      dimension_(dimension),
      dF_(dimension, window_),
      dG_(dimension, window_),
      ff_(Eigen::MatrixXd::Zero(window_, window_)),
      fg_(Eigen::MatrixXd::Zero(window_, window_)),
      gg_(Eigen::MatrixXd::Zero(window_, window_)),
      f_on_dF_(Eigen::VectorXd::Zero(window_)) {}

double SecantHistory::add(const Eigen::Ref<const Eigen::VectorXd>& x,
                          const Eigen::Ref<const Eigen::VectorXd>& g, HelperThread* threads) {
  const Eigen::Index n = dimension_;
  if (!has_previous_) {
    previous_f_ = g - x;
    previous_g_ = g;
    has_previous_ = true;
    return largest_triple(previous_f_.data(), n);
  }
  const int newest = static_cast<int>(pairs_ % window_);
  ++pairs_;
  const int m = stored();
  std::array<std::vector<double>, 2> sums;
  std::array<double, 2> largest{0.0, 0.0};
  auto part = [&](int p) {
    std::vector<double>& s = sums[static_cast<std::size_t>(p)];
    s.assign(static_cast<std::size_t>(kSums * m), 0.0);
    const Eigen::Index begin = half_begin(p, n, 3), end = half_end(p, n, 3);
    double big = 0.0;
    for (Eigen::Index c0 = begin; c0 < end; c0 += kChunk) {
      const Eigen::Index length = std::min(kChunk, end - c0);
      double* df = dF_.col(newest).data() + c0;
      double* dg = dG_.col(newest).data() + c0;
      double* pf = previous_f_.data() + c0;
      double* pg = previous_g_.data() + c0;
      const double* xs = x.data() + c0;
      const double* gs = g.data() + c0;
      for (Eigen::Index i = 0; i < length; ++i) {
        const double fi = gs[i] - xs[i];
        df[i] = fi - pf[i];
        dg[i] = gs[i] - pg[i];
        pf[i] = fi;
        pg[i] = gs[i];
      }
      big = std::max(big, largest_triple(pf, length));
      const Eigen::Map<const Eigen::VectorXd> new_f(df, length), new_g(dg, length), f(pf, length);
      for (int k = 0; k < m; ++k) {
        const int ck = column(k);
        const Eigen::Map<const Eigen::VectorXd> fk(dF_.col(ck).data() + c0, length),
            gk(dG_.col(ck).data() + c0, length);
        double* sk = s.data() + kSums * k;
        sk[0] += new_f.dot(fk);
        sk[1] += new_f.dot(gk);
        sk[2] += fk.dot(new_g);
        sk[3] += new_g.dot(gk);
        sk[4] += fk.dot(f);
      }
    }
    largest[static_cast<std::size_t>(p)] = big;
  };
  run_halves(threads, part);
  for (int k = 0; k < m; ++k) {
    const int ck = column(k);
    auto sum = [&](int which) {
      return sums[0][static_cast<std::size_t>(kSums * k + which)] +
             sums[1][static_cast<std::size_t>(kSums * k + which)];
    };
    ff_(newest, ck) = ff_(ck, newest) = sum(0);
    fg_(newest, ck) = sum(1);
    fg_(ck, newest) = sum(2);
    gg_(newest, ck) = gg_(ck, newest) = sum(3);
    f_on_dF_(ck) = sum(4);
  }
  return std::max(largest[0], largest[1]);
}

bool SecantHistory::extrapolate(const Eigen::Ref<const Eigen::VectorXd>& g, const Eigen::VectorXd& gamma,
                                Eigen::Ref<Eigen::VectorXd> out, HelperThread* threads) const {
  const Eigen::Index n = dimension_;
  const int m = static_cast<int>(std::min<Eigen::Index>(gamma.size(), stored()));
  std::array<bool, 2> finite{true, true};
  auto part = [&](int p) {
    const Eigen::Index begin = half_begin(p, n, 3), end = half_end(p, n, 3);
    bool ok = true;
    for (Eigen::Index c0 = begin; c0 < end; c0 += kChunk) {
      const Eigen::Index length = std::min(kChunk, end - c0);
      auto o = out.segment(c0, length);
      o = g.segment(c0, length);
      for (int k = 0; k < m; ++k) o -= gamma(k) * dG_.col(column(k)).segment(c0, length);
      ok = ok && o.allFinite();
    }
    finite[static_cast<std::size_t>(p)] = ok;
  };
  run_halves(threads, part);
  return finite[0] && finite[1];
}

}  // namespace pushpull::deform::detail
