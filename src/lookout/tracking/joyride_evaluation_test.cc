// The IMM on real radar data: the "joyride" data set of the NTNU sensor-fusion course (TTK4250),
// a boat tracked by a marine radar with clutter, with GNSS truth. docs/imm.md describes the data,
// the tracker, the tuning and the figures this test prints.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "lookout/core/input_error.h"
#include "lookout/io/mat_file.h"
#include "lookout/tracking/nearest_neighbour_tracker.h"

namespace lookout::tracking {
namespace {

struct Joyride {
  std::vector<TimeNs> times;          // from the first scan
  Eigen::MatrixXd truth;              // 4 x K: x, y, vx, vy
  std::vector<Eigen::MatrixXd> scans;  // 2 x m_k
  std::vector<bool> manoeuvring;      // |truth turn rate| above the threshold
  std::vector<double> turn_rate;      // of the truth, rad/s
};

// Turn rates above this (5.7 deg/s, the truth's 75th percentile; its median, 0.05 rad/s, is
// mostly GNSS velocity noise) mark the manoeuvres.
constexpr double kManoeuvreTurnRate = 0.1;

Joyride LoadJoyride() {
  const std::string path = std::string(LOOKOUT_SOURCE_DIR) + "/../shared/data/imm/joyridedata.mat";
  const io::MatFile file = io::ReadMatFile(path);
  Joyride data;
  data.truth = file.Matrix("Xgt");
  data.scans = file.Cells("Z");
  const Eigen::MatrixXd& time = file.Matrix("time");
  const auto k = static_cast<std::size_t>(data.truth.cols());
  if (data.scans.size() != k || static_cast<std::size_t>(time.size()) != k) {
    throw InputError(path, 0, "Z", "Xgt, Z and time must have one entry per scan");
  }
  for (std::size_t i = 0; i < k; ++i) {
    const TimeNs t = FromSeconds(time(static_cast<Eigen::Index>(i)) - time(0));
    if (i > 0 && t <= data.times.back()) {
      throw InputError(path, 0, "time(" + std::to_string(i + 1) + ")", "time does not increase");
    }
    data.times.push_back(t);
  }
  // The truth's turn rate by central differences of its heading.
  data.turn_rate.assign(k, 0.0);
  for (std::size_t i = 1; i + 1 < k; ++i) {
    const auto a = static_cast<Eigen::Index>(i - 1), b = static_cast<Eigen::Index>(i + 1);
    double dh = std::atan2(data.truth(3, b), data.truth(2, b)) -
                std::atan2(data.truth(3, a), data.truth(2, a));
    dh = std::remainder(dh, 2.0 * std::numbers::pi);
    data.turn_rate[i] = dh / ToSeconds(data.times[i + 1] - data.times[i - 1]);
  }
  for (std::size_t i = 0; i < k; ++i) {
    data.manoeuvring.push_back(std::abs(data.turn_rate[i]) > kManoeuvreTurnRate);
  }
  return data;
}

struct Figures {
  double pos_rmse = 0.0, vel_rmse = 0.0, nees = 0.0, nis = 0.0;
  int scans = 0, associated = 0;
};

struct Evaluation {
  Figures all, manoeuvring;
};

Evaluation Evaluate(const TrackerOptions& options, const Joyride& data) {
  options.Validate("joyride", "tracker");
  const double s2 = options.measurement_std_m * options.measurement_std_m;
  // Started from the first truth state with the uncertainty of one measurement and 10 m/s:
  // initiation is the MHT's job, this measures the filter.
  const Gaussian prior{data.truth.col(0), Eigen::Vector4d(s2, s2, 100.0, 100.0).asDiagonal()};
  ImmState state = InitImm(options.imm, prior, {kX, kY, kVx, kVy}, 1.0, data.times[0]);
  struct Sum {
    double pos = 0, vel = 0, nees = 0, nis = 0;
    int n = 0, associated = 0;
  } all, man;
  for (std::size_t k = 1; k < data.scans.size(); ++k) {
    const TrackStep step = TrackScan(options, state, data.times[k], data.scans[k]);
    state = step.state;
    const Gaussian g = Combine(options.imm, state);
    const Eigen::Vector4d e = g.mean - data.truth.col(static_cast<Eigen::Index>(k));
    for (Sum* s : {&all, data.manoeuvring[k] ? &man : nullptr}) {
      if (s == nullptr) continue;
      s->pos += e.head<2>().squaredNorm();
      s->vel += e.tail<2>().squaredNorm();
      s->nees += NormalisedSquare(e, g.cov);
      ++s->n;
      if (step.associated) {
        s->nis += step.nis;
        ++s->associated;
      }
    }
  }
  const auto finish = [](const Sum& s) {
    Figures f;
    f.scans = s.n;
    f.associated = s.associated;
    f.pos_rmse = std::sqrt(s.pos / s.n);
    f.vel_rmse = std::sqrt(s.vel / s.n);
    f.nees = s.nees / s.n;
    f.nis = s.associated > 0 ? s.nis / s.associated : 0.0;
    return f;
  };
  return {finish(all), finish(man)};
}

// The tuned parameters: for each filter, the grid point of DISABLED_GridSearch with the lowest
// whole-run position RMSE (chosen before looking at the manoeuvring figures). docs/imm.md.
constexpr double kSigmaM = 20.0;
constexpr double kImmCvPsd = 0.1;
constexpr double kImmCaPsd = 0.01;
constexpr double kImmTurnRate = 0.15;
constexpr double kImmTurnPsd = 2.0;
constexpr double kImmStay = 0.8;
constexpr double kImmGate = 0.9999;
constexpr double kCvPsd = 10.0;
constexpr double kCvGate = 0.999;
constexpr double kCtrCvPsd = 2.0;
constexpr double kCtrRatePsd = 0.01;
constexpr double kCtrStay = 0.8;
constexpr double kCtrGate = 0.999;

TrackerOptions ImmTracker(double sigma, double cv, double ca, double rate, double turn,
                          double stay) {
  TrackerOptions o;
  o.imm = FourModelImm(cv, ca, rate, turn, stay);
  o.measurement_std_m = sigma;
  return o;
}

TrackerOptions CvTracker(double sigma, double cv) {
  TrackerOptions o;
  o.imm.models = {ConstantVelocity(cv)};
  o.imm.transition = Eigen::MatrixXd::Ones(1, 1);
  o.imm.initial_probabilities = Eigen::VectorXd::Ones(1);
  o.measurement_std_m = sigma;
  return o;
}

// CV and a turn-rate-state model (the NTNU course's pair).
TrackerOptions CvCtrTracker(double sigma, double cv, double rate_psd, double stay) {
  TrackerOptions o;
  o.imm.models = {ConstantVelocity(cv), CoordinatedTurnRate(cv, rate_psd)};
  o.imm.transition = Eigen::Matrix2d{{stay, 1.0 - stay}, {1.0 - stay, stay}};
  o.imm.initial_probabilities = Eigen::Vector2d(0.5, 0.5);
  o.measurement_std_m = sigma;
  return o;
}

void Print(const char* name, const Evaluation& e) {
  for (const auto& [part, f] : {std::pair{"all", e.all}, std::pair{"manoeuvring", e.manoeuvring}}) {
    std::printf("%-12s %-12s scans %3d assoc %3d  pos RMSE %6.2f m  vel RMSE %5.2f m/s  "
                "NEES %6.2f  NIS %5.2f\n",
                name, part, f.scans, f.associated, f.pos_rmse, f.vel_rmse, f.nees, f.nis);
  }
}

TEST(JoyrideEvaluation, ImmBeatsConstantVelocityDuringManoeuvres) {
  const Joyride data = LoadJoyride();
  TrackerOptions imm_options =
      ImmTracker(kSigmaM, kImmCvPsd, kImmCaPsd, kImmTurnRate, kImmTurnPsd, kImmStay);
  imm_options.gate_probability = kImmGate;
  TrackerOptions cv_options = CvTracker(kSigmaM, kCvPsd);
  cv_options.gate_probability = kCvGate;
  TrackerOptions ctr_options = CvCtrTracker(kSigmaM, kCtrCvPsd, kCtrRatePsd, kCtrStay);
  ctr_options.gate_probability = kCtrGate;
  const Evaluation imm = Evaluate(imm_options, data);
  const Evaluation cv = Evaluate(cv_options, data);
  const Evaluation ctr = Evaluate(ctr_options, data);
  Print("IMM CV+CA+CT", imm);
  Print("IMM CV+CTR", ctr);
  Print("CV alone", cv);
  EXPECT_EQ(imm.manoeuvring.scans, 49);
  EXPECT_LT(imm.manoeuvring.pos_rmse, cv.manoeuvring.pos_rmse);
  EXPECT_LT(imm.manoeuvring.vel_rmse, cv.manoeuvring.vel_rmse);
  EXPECT_LT(ctr.manoeuvring.pos_rmse, cv.manoeuvring.pos_rmse);
  EXPECT_LT(ctr.manoeuvring.vel_rmse, cv.manoeuvring.vel_rmse);
  // And over the whole run; all three keep the track (170 of 199 scans associated).
  EXPECT_LT(imm.all.pos_rmse, cv.all.pos_rmse);
  EXPECT_LT(imm.all.vel_rmse, cv.all.vel_rmse);
  EXPECT_GE(imm.all.associated, 165);
}

// Same input, same output bits: the evaluation twice.
TEST(JoyrideEvaluation, IsDeterministic) {
  const Joyride data = LoadJoyride();
  TrackerOptions o = ImmTracker(kSigmaM, kImmCvPsd, kImmCaPsd, kImmTurnRate, kImmTurnPsd, kImmStay);
  const Evaluation a = Evaluate(o, data);
  const Evaluation b = Evaluate(o, data);
  EXPECT_EQ(a.all.pos_rmse, b.all.pos_rmse);
  EXPECT_EQ(a.all.nees, b.all.nees);
}

// The tuning: run with --gtest_also_run_disabled_tests --gtest_filter='*GridSearch*'.
TEST(JoyrideEvaluation, DISABLED_GridSearch) {
  const Joyride data = LoadJoyride();
  std::vector<double> rates;
  for (const double w : data.turn_rate) rates.push_back(std::abs(w));
  std::sort(rates.begin(), rates.end());
  std::printf("|turn rate| percentiles 25/50/75/90: %.3f %.3f %.3f %.3f rad/s\n", rates[50],
              rates[100], rates[150], rates[180]);
  int man = 0;
  for (const bool m : data.manoeuvring) man += m ? 1 : 0;
  std::printf("manoeuvring scans: %d of %zu\n", man, data.manoeuvring.size());
  const auto line = [](const char* name, const Evaluation& e) {
    std::printf("%s | all pos %7.2f vel %5.2f NEES %7.2f NIS %5.2f assoc %3d | man pos %7.2f vel "
                "%5.2f\n",
                name, e.all.pos_rmse, e.all.vel_rmse, e.all.nees, e.all.nis, e.all.associated,
                e.manoeuvring.pos_rmse, e.manoeuvring.vel_rmse);
  };
  char name[160];
  for (const double gate : {0.999, 0.9999}) {
    for (const double sigma : {10.0, 15.0, 20.0, 25.0}) {
      for (const double cv : {1.0, 2.0, 5.0, 10.0, 20.0}) {
        TrackerOptions o = CvTracker(sigma, cv);
        o.gate_probability = gate;
        std::snprintf(name, sizeof name, "CV  gate %.3f sigma %4.1f q %5.2f", gate, sigma, cv);
        line(name, Evaluate(o, data));
      }
    }
  }
  for (const double gate : {0.999, 0.9999}) {
    for (const double sigma : {15.0, 20.0, 25.0}) {
      for (const double cv : {0.1, 0.5, 2.0}) {
        for (const double rate : {0.05, 0.1, 0.15, 0.2}) {
          for (const double turn : {0.1, 0.5, 2.0}) {
            for (const double stay : {0.8, 0.9}) {
              TrackerOptions o = ImmTracker(sigma, cv, 0.01, rate, turn, stay);
              o.gate_probability = gate;
              std::snprintf(name, sizeof name,
                            "IMM gate %.4f sigma %4.1f q %5.2f w %4.2f qt %4.2f stay %4.2f", gate,
                            sigma, cv, rate, turn, stay);
              line(name, Evaluate(o, data));
            }
          }
        }
        for (const double rate_psd : {1e-3, 1e-2, 1e-1}) {
          for (const double stay : {0.8, 0.9}) {
            TrackerOptions o = CvCtrTracker(sigma, cv, rate_psd, stay);
            o.gate_probability = gate;
            std::snprintf(name, sizeof name,
                          "CTR gate %.4f sigma %4.1f q %5.2f qw %6.4f stay %4.2f", gate, sigma, cv,
                          rate_psd, stay);
            line(name, Evaluate(o, data));
          }
        }
      }
    }
  }
}

}  // namespace
}  // namespace lookout::tracking
