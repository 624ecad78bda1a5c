// Which keys the logs determine, from their sensitivities: none that no stretch depends on
// (not in the logs); by a QR with column pivoting of the unit columns, none that the others
// already explain (cannot be told apart); and no planned key whose expected standard error is
// above half its value (barely told). The last two are found in turn, so that a key held as like
// another is looked at again once that other is held as barely told.
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "timing_model.hpp"

namespace ncjoule::timing_detail {

KeySelection select_keys(const std::vector<KeyColumn>& columns, const Eigen::VectorXd& misfit,
                         double sigma_s) {
  const std::size_t n_obs = std::size_t(misfit.size());
  KeySelection out;
  std::vector<char>& keep = out.keep;
  std::map<std::size_t, std::string>& held_why = out.why;
  keep.assign(columns.size(), 1);
  for (std::size_t c = 0; c < columns.size(); ++c) {
    // A stretch is known to a tenth of a second: a key that moves no stretch by a millisecond
    // for a 10% change (or one second of its own) is not in these logs.
    const double effect =
        columns[c].values.cwiseAbs().maxCoeff() * (columns[c].theta ? 0.1 : 1.0) * sigma_s;
    if (!(effect > 1e-3)) {
      keep[c] = 0;
      held_why[c] = columns[c].theta
                        ? "not in the logs (no logged stretch depends on it: no move reaches it)"
                        : "not in the logs (no logged stretch depends on it)";
    }
  }
  // Collinear keys (QR) and keys barely told are found in turn: a key held as like another is
  // looked at again once that other is held as barely told.
  const std::vector<char> in_logs = keep;
  std::vector<char> barely(columns.size(), 0);
  for (int pass = 0; pass < 3; ++pass) {
    bool more = false;
    for (std::size_t c = 0; c < columns.size(); ++c) {
      keep[c] = in_logs[c] && !barely[c];
      if (keep[c]) held_why.erase(c);
    }
    {
      std::vector<std::size_t> live;
      for (std::size_t c = 0; c < columns.size(); ++c)
        if (keep[c]) live.push_back(c);
      if (!live.empty()) {
        Eigen::MatrixXd a(Eigen::Index(n_obs), Eigen::Index(live.size()));
        for (std::size_t i = 0; i < live.size(); ++i)
          a.col(Eigen::Index(i)) = columns[live[i]].values.normalized();
        Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(a);
        const Eigen::MatrixXd r = qr.matrixR().template triangularView<Eigen::Upper>();
        const auto& perm = qr.colsPermutation().indices();
        const double r0 = std::abs(r(0, 0));
        for (Eigen::Index i = 0; i < Eigen::Index(live.size()); ++i) {
          if (std::abs(r(i, i)) >= 0.05 * r0) continue; // explains at least 5% on its own
          const std::size_t c = live[std::size_t(perm[i])];
          keep[c] = 0;
          // The kept column it resembles most.
          double best = 0;
          std::string like;
          for (std::size_t d : live)
            if (keep[d] && d != c) {
              const double cs = std::abs(cosine(columns[c].values, columns[d].values));
              if (cs > best) {
                best = cs;
                like = columns[d].label;
              }
            }
          char text[256];
          std::snprintf(text, sizeof text,
                        "cannot be told apart from %s in these logs (their effects on the logged "
                        "stretches correlate at %.2f)",
                        like.c_str(), best);
          held_why[c] = text;
        }
      }
    }
    // A planned key the logs barely tell (its expected standard error, from the sensitivities and
    // the base's misfit, above half its value) is held too: fitted, it would only soak up misfit.
    {
      std::vector<std::size_t> live;
      for (std::size_t c = 0; c < columns.size(); ++c)
        if (keep[c]) live.push_back(c);
      if (!live.empty()) {
        Eigen::MatrixXd a(Eigen::Index(n_obs), Eigen::Index(live.size()));
        for (std::size_t i = 0; i < live.size(); ++i)
          a.col(Eigen::Index(i)) = columns[live[i]].values;
        const Eigen::MatrixXd info = a.transpose() * a;
        const Eigen::MatrixXd cov = info.completeOrthogonalDecomposition().pseudoInverse();
        // The misfit left after one linearised step from the base (what the fit will leave, in
        // stretch standard deviations) scales the standard errors.
        const Eigen::VectorXd step = cov * (a.transpose() * misfit);
        const Eigen::VectorXd left = misfit - a * step;
        const double inflation = std::max(1.0, std::sqrt(left.squaredNorm() / double(n_obs)));
        for (std::size_t i = 0; i < live.size(); ++i) {
          const KeyColumn& col = columns[live[i]];
          if (!col.theta) continue;
          const double scale = col.scale;
          const double se =
              std::sqrt(std::max(0.0, cov(Eigen::Index(i), Eigen::Index(i)))) * inflation;
          if (se > 0.5 * scale) {
            keep[live[i]] = 0;
            barely[live[i]] = 1;
            more = true;
            char text[200];
            std::snprintf(
                text, sizeof text,
                "the logs barely tell it (it would come out within +- %.0f%% of its value)",
                100 * se / scale);
            held_why[live[i]] = text;
          }
        }
      }
    }
    if (!more) break;
  }
  return out;
}

} // namespace ncjoule::timing_detail
