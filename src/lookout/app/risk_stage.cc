#include "lookout/app/risk_stage.h"

#include <chrono>
#include <cmath>

#include "lookout/core/input_error.h"

namespace lookout::app {
namespace {

using Clock = std::chrono::steady_clock;

}  // namespace

std::optional<EgoPrediction> ParseEgoPrediction(const std::string& name) {
  if (name == "route") return EgoPrediction::kRoute;
  if (name == "heading") return EgoPrediction::kHeading;
  if (name == "yaw-rate") return EgoPrediction::kYawRate;
  return std::nullopt;
}

const char* ToString(EgoPrediction prediction) {
  switch (prediction) {
    case EgoPrediction::kRoute: return "route";
    case EgoPrediction::kHeading: return "heading";
    case EgoPrediction::kYawRate: return "yaw-rate";
  }
  return "route";
}

void RiskStageOptions::Validate(const std::string& source) const {
  risk.Validate(source + ": risk");
  warnings.Validate(source + ": warnings");
  if (!std::isfinite(acceleration_window_s) || acceleration_window_s <= 0.0) {
    throw InputError(source, 0, "acceleration_window_s", "must be > 0");
  }
}

risk::EgoInput InterpretEgo(TimeNs stamp, const Pose2& ego_pose,
                            const std::deque<EgoOdometry>& odometry, double window_s) {
  risk::EgoInput ego;
  ego.position_m = ego_pose.translation;
  ego.yaw_rad = ego_pose.yaw;
  // Least-squares line v = v0 + a (t - stamp) through the readings of the window.
  double n = 0.0, st = 0.0, sv = 0.0, stt = 0.0, stv = 0.0;
  const EgoOdometry* latest = nullptr;
  for (const EgoOdometry& o : odometry) {
    if (o.stamp > stamp) break;
    latest = &o;
    const double t = ToSeconds(o.stamp - stamp);
    if (t < -window_s) continue;
    n += 1.0;
    st += t;
    sv += o.speed_mps;
    stt += t * t;
    stv += t * o.speed_mps;
  }
  if (!latest) return ego;
  ego.yaw_rate_radps = latest->yaw_rate_radps;
  const double det = n * stt - st * st;
  if (n >= 3.0 && det > 1e-12) {
    ego.acceleration_mps2 = (n * stv - st * sv) / det;
    ego.speed_mps = std::max(0.0, (sv - ego.acceleration_mps2 * st) / n);
  } else {
    ego.speed_mps = latest->speed_mps;
  }
  return ego;
}

std::vector<risk::ObjectInput> InterpretTracks(const std::vector<tracking::Track>& tracks) {
  std::vector<risk::ObjectInput> out;
  out.reserve(tracks.size());
  for (const tracking::Track& t : tracks) {
    risk::ObjectInput o;
    o.id = t.id;
    o.object_class = t.object_class;
    o.position_m = t.Position();
    o.velocity_mps = t.Velocity();
    o.position_covariance = t.state.cov.topLeftCorner<2, 2>();
    o.velocity_covariance = t.state.cov.block<2, 2>(2, 2);
    out.push_back(o);
  }
  return out;
}

RiskStage::RiskStage(const RiskStageOptions& options)
    : options_(options), warnings_(options.warnings) {
  options_.Validate();
  options_.risk.hold_yaw_rate = options_.ego_prediction == EgoPrediction::kYawRate;
}

void RiskStage::OnOdometry(const EgoOdometry& odometry) {
  if (!odometry_.empty() && odometry.stamp <= odometry_.back().stamp) return;
  if (!std::isfinite(odometry.speed_mps) || !std::isfinite(odometry.yaw_rate_radps)) return;
  odometry_.push_back(odometry);
  // Keep a little more than the window (a cycle's worth of readings may come before the scan).
  const TimeNs keep = FromSeconds(options_.acceleration_window_s + 0.5);
  while (odometry_.size() > 1 && odometry_.back().stamp - odometry_.front().stamp > keep) {
    odometry_.pop_front();
  }
}

void RiskStage::SetRoute(std::vector<Eigen::Vector2d> route_m) {
  for (const Eigen::Vector2d& p : route_m) {
    if (!p.allFinite()) throw InputError("route", 0, "route", "has a non-finite point");
  }
  route_ = std::move(route_m);
}

void RiskStage::SetCarriageways(risk::Carriageways roads_m) {
  carriageways_ = std::move(roads_m);
}

void RiskStage::Step(TimeNs stamp, const Pose2& ego_pose,
                     const std::vector<tracking::Track>& tracks) {
  if (last_stamp_ && stamp <= *last_stamp_) {
    ++refused_;
    return;
  }
  const Clock::time_point start = Clock::now();
  ego_ = InterpretEgo(stamp, ego_pose, odometry_, options_.acceleration_window_s);
  if (options_.ego_prediction == EgoPrediction::kRoute) ego_.route_m = route_;
  ego_.carriageways_m = carriageways_;
  assessment_ = risk::AssessRisk(ego_, InterpretTracks(tracks), options_.risk);
  dropped_ += static_cast<std::int64_t>(assessment_.dropped);
  warnings_.Update(stamp, assessment_);
  step_ms_.push_back(std::chrono::duration<double, std::milli>(Clock::now() - start).count());
  last_stamp_ = stamp;
}

}  // namespace lookout::app
