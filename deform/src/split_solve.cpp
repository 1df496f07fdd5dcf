// GlobalSystem's triangular solves, split along the elimination tree of L into two groups of disjoint
// subtrees (independent: a column only updates its etree ancestors) and the remaining ancestors ("top").
#include <algorithm>
#include <cstddef>

#include "global_system.hpp"

namespace pushpull::deform::detail {

void GlobalSystem::plan_split() {
  const int n = n_free_;
  const int* outer = l_column_;
  const int* inner = l_row_;
  const int skip = l_diagonal_slots_;  // column j's strictly lower entries: [outer[j] + skip, outer[j + 1])
  const int nonzeros = outer[n];
  // Refactorizations keep the symbolic pattern: plan again only if the factor's pattern differs.
  if (planned_outer_.size() == static_cast<std::size_t>(n) + 1 &&
      std::equal(planned_outer_.begin(), planned_outer_.end(), outer) &&
      std::equal(planned_inner_.begin(), planned_inner_.end(), inner, inner + nonzeros)) {
    return;
  }
  planned_outer_.assign(outer, outer + n + 1);
  planned_inner_.assign(inner, inner + nonzeros);
  // Elimination tree (parent = smallest row below the diagonal) and per-subtree solve work.
  std::vector<int> parent(static_cast<std::size_t>(n), -1), child_start(static_cast<std::size_t>(n) + 1, 0);
  std::vector<long> work(static_cast<std::size_t>(n), 0);
  for (int j = 0; j < n; ++j) {
    int lowest = n;
    for (int p = outer[j] + skip; p < outer[j + 1]; ++p) lowest = std::min(lowest, inner[p]);
    parent[static_cast<std::size_t>(j)] = lowest < n ? lowest : -1;
    work[static_cast<std::size_t>(j)] += outer[j + 1] - outer[j] - skip + 1;
  }
  for (int j = 0; j < n; ++j) {  // children precede parents: subtree sums in one ascending pass
    const int up = parent[static_cast<std::size_t>(j)];
    if (up >= 0)
      work[static_cast<std::size_t>(up)] += work[static_cast<std::size_t>(j)],
          ++child_start[static_cast<std::size_t>(up) + 1];
  }
  for (int j = 0; j < n; ++j)
    child_start[static_cast<std::size_t>(j) + 1] += child_start[static_cast<std::size_t>(j)];
  std::vector<int> children(static_cast<std::size_t>(std::max(n, 1))),
      fill(child_start.begin(), child_start.end() - 1);
  long total = 0;
  std::vector<int> frontier;  // subtree roots
  for (int j = 0; j < n; ++j) {
    const int up = parent[static_cast<std::size_t>(j)];
    if (up >= 0)
      children[static_cast<std::size_t>(fill[static_cast<std::size_t>(up)]++)] = j;
    else
      frontier.push_back(j), total += work[static_cast<std::size_t>(j)];
  }
  // Greedy: move the heaviest subtree's root to the top until the subtrees pack into two balanced bins;
  // keep the split with the shortest critical path (top + heavier bin).
  auto heavier = [&](int a, int b) {
    return work[static_cast<std::size_t>(a)] != work[static_cast<std::size_t>(b)]
               ? work[static_cast<std::size_t>(a)] > work[static_cast<std::size_t>(b)]
               : a < b;
  };
  // Greedy list scheduling of the (heaviest-first) subtrees onto the two parts.
  auto pack = [&](const std::vector<int>& roots, std::vector<int>* bins) {
    long load[2] = {0, 0};
    for (int r : roots) {
      const int b = load[0] <= load[1] ? 0 : 1;
      if (bins) bins[b].push_back(r);
      load[b] += work[static_cast<std::size_t>(r)];
    }
    return std::max(load[0], load[1]);
  };
  std::vector<int> top, best_frontier;
  std::size_t best_top_count = 0;
  long top_work = 0, best_critical = total + 1;
  std::sort(frontier.begin(), frontier.end(), heavier);
  // A lone subtree (the chain of a nested-dissection separator) cannot be split: rounds spent walking down
  // it do not count against the patience, else deep separators would stop the search before any split.
  for (int round = 0, since_best = 0; round < 65536 && since_best < 256 && !frontier.empty();
       ++round, since_best += frontier.size() > 1 ? 1 : 0) {
    const long heavier_part = pack(frontier, nullptr);
    if (top_work + heavier_part < best_critical) {
      best_critical = top_work + heavier_part;
      since_best = -1;
      best_top_count = top.size();
      best_frontier = frontier;
    }
    if (2 * heavier_part <= total + total / 25 || 4 * top_work > total) break;
    const int root = frontier.front();
    frontier.erase(frontier.begin());
    top.push_back(root);
    long own = work[static_cast<std::size_t>(root)];
    const std::size_t old_size = frontier.size();
    for (int k = child_start[static_cast<std::size_t>(root)];
         k < child_start[static_cast<std::size_t>(root) + 1]; ++k) {
      frontier.push_back(children[static_cast<std::size_t>(k)]);
      own -= work[static_cast<std::size_t>(children[static_cast<std::size_t>(k)])];
    }
    std::sort(frontier.begin() + static_cast<std::ptrdiff_t>(old_size), frontier.end(), heavier);
    std::inplace_merge(frontier.begin(), frontier.begin() + static_cast<std::ptrdiff_t>(old_size),
                       frontier.end(), heavier);
    top_work += own;
  }
  const std::vector<int> best_top(top.begin(), top.begin() + static_cast<std::ptrdiff_t>(best_top_count));
  std::vector<int> best_bins[2];
  pack(best_frontier, best_bins);
  // Column -> part (0, 1) or top (2); subtrees take their root's part.
  std::vector<char> part(static_cast<std::size_t>(n), 2), is_top(static_cast<std::size_t>(n), 0);
  for (int j : best_top) is_top[static_cast<std::size_t>(j)] = 1;
  for (int b = 0; b < 2; ++b) {
    for (int r : best_bins[b]) part[static_cast<std::size_t>(r)] = static_cast<char>(b);
  }
  for (int j = n - 1; j >= 0; --j) {  // parents precede children in descending order
    const int up = parent[static_cast<std::size_t>(j)];
    if (up >= 0 && part[static_cast<std::size_t>(j)] == 2 && !is_top[static_cast<std::size_t>(j)]) {
      part[static_cast<std::size_t>(j)] = part[static_cast<std::size_t>(up)];
    }
  }
  std::vector<int> top_slot(static_cast<std::size_t>(n), -1);
  for (int b = 0; b < 2; ++b) part_columns_[b].clear();
  top_columns_.clear();
  for (int j = 0; j < n; ++j) {
    const char pj = part[static_cast<std::size_t>(j)];
    if (pj == 2) {
      top_slot[static_cast<std::size_t>(j)] = static_cast<int>(top_columns_.size());
      top_columns_.push_back(j);
    } else {
      part_columns_[static_cast<std::size_t>(pj)].push_back(j);
    }
  }
  const int top_count = static_cast<int>(top_columns_.size());
  forward_target_.assign(inner, inner + nonzeros);
  for (int j = 0; j < n; ++j) {
    const char pj = part[static_cast<std::size_t>(j)];
    if (pj == 2) continue;
    for (int p = outer[j] + skip; p < outer[j + 1]; ++p) {
      const int slot = top_slot[static_cast<std::size_t>(inner[p])];
      if (slot >= 0) forward_target_[static_cast<std::size_t>(p)] = n + pj * top_count + slot;
    }
  }
}

void GlobalSystem::solve_in_place(Eigen::Matrix3Xd& B, HelperThread* threads) const {
  const int n = n_free_;
  if (n == 0) return;
  const int top_count = static_cast<int>(top_columns_.size());
  Eigen::Matrix3Xd W = Eigen::Matrix3Xd::Zero(3, n + 2 * top_count);  // Y, then the parts' accumulators
  for (int i = 0; i < n; ++i) W.col(perm_(i)) = B.col(i);
  const int* outer = l_column_;  // unit lower triangular L, strictly lower entries from outer[j] + skip
  const int* inner = l_row_;
  const int skip = l_diagonal_slots_;
  const int* target = forward_target_.data();
  const double* value = l_value_;
  double* w = W.data();
  // L y = b: column j, once final, updates the rows below it (its etree ancestors).
  auto forward = [&](int j) {
    const double y0 = w[3 * j], y1 = w[3 * j + 1], y2 = w[3 * j + 2];
    for (int p = outer[j] + skip; p < outer[j + 1]; ++p) {
      double* t = w + 3 * static_cast<std::ptrdiff_t>(target[p]);
      t[0] -= value[p] * y0;
      t[1] -= value[p] * y1;
      t[2] -= value[p] * y2;
    }
  };
  // L^T x = y: column j gathers from the rows below it (final by then).
  auto backward = [&](int j) {
    double a0 = w[3 * j], a1 = w[3 * j + 1], a2 = w[3 * j + 2];
    for (int p = outer[j] + skip; p < outer[j + 1]; ++p) {
      const double* x = w + 3 * static_cast<std::ptrdiff_t>(inner[p]);
      a0 -= value[p] * x[0];
      a1 -= value[p] * x[1];
      a2 -= value[p] * x[2];
    }
    w[3 * j] = a0, w[3 * j + 1] = a1, w[3 * j + 2] = a2;
  };
  auto forward_part = [&](int p) {
    for (int j : part_columns_[p]) forward(j);
  };
  auto backward_part = [&](int p) {
    const std::vector<int>& columns = part_columns_[p];
    for (auto it = columns.rbegin(); it != columns.rend(); ++it) backward(*it);
  };
  auto both = [&](auto& job) { run_halves(threads, job); };
  both(forward_part);
  for (int s = 0; s < top_count; ++s) {  // the parts' updates of top rows, in part order
    const int i = top_columns_[static_cast<std::size_t>(s)];
    W.col(i) += W.col(n + s);
    W.col(i) += W.col(n + top_count + s);
  }
  for (int j : top_columns_) forward(j);  // top columns only update top rows
  for (int j = 0; j < n; ++j) W.col(j) *= inv_d_(j);
  for (auto it = top_columns_.rbegin(); it != top_columns_.rend(); ++it) backward(*it);
  both(backward_part);
  for (int i = 0; i < n; ++i) B.col(i) = W.col(perm_(i));
}

}  // namespace pushpull::deform::detail
