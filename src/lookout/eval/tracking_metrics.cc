#include "lookout/eval/tracking_metrics.h"

#include <cmath>

namespace lookout::eval {
namespace {

std::vector<Eigen::Vector2d> Positions(const std::vector<PointObject>& objects) {
  std::vector<Eigen::Vector2d> out;
  out.reserve(objects.size());
  for (const PointObject& o : objects) out.push_back(o.position_m);
  return out;
}

}  // namespace

TrackingMetricsAccumulator::TrackingMetricsAccumulator(const TrackingMetricOptions& options)
    : options_(options) {}

void TrackingMetricsAccumulator::AddFrame(const std::vector<PointObject>& truths,
                                          const std::vector<PointObject>& tracks) {
  evaluator_.AddFrame(DistanceFrame(truths, tracks, options_.match_distance_m));
  const GospaResult g = Gospa(Positions(truths), Positions(tracks), options_.gospa);
  ++frames_;
  gospa_sum_ += g.distance;
  localisation_sum_ += g.localisation_pth;
  missed_sum_ += g.missed_pth;
  false_sum_ += g.false_pth;
}

double TrackingMetricsAccumulator::MeanGospa() const {
  return frames_ > 0 ? gospa_sum_ / static_cast<double>(frames_) : std::nan("");
}

std::map<std::string, double> TrackingMetricsAccumulator::Values(const std::string& prefix) const {
  std::map<std::string, double> v;
  const TrackingScores s = evaluator_.Scores();
  const ClearMotCounts& c = s.clear;
  auto put = [&](const char* key, double value) {
    if (std::isfinite(value)) v[prefix + "." + key] = value;
  };
  put("frames", static_cast<double>(frames_));
  if (frames_ == 0) return v;
  const double n = static_cast<double>(frames_);
  const double p = options_.gospa.order_p;
  put("gospa_m", gospa_sum_ / n);
  put("gospa_localisation_m", std::pow(localisation_sum_ / n, 1.0 / p));
  put("gospa_missed_m", std::pow(missed_sum_ / n, 1.0 / p));
  put("gospa_false_m", std::pow(false_sum_ / n, 1.0 / p));
  put("false_positives", static_cast<double>(c.false_positives));
  put("truths", static_cast<double>(c.unique_truths));
  if (c.truth_objects == 0) return v;
  put("mota", c.Mota());
  put("motp_m", c.Motp());
  put("id_switches", static_cast<double>(c.switches));
  put("recall", c.Recall());
  put("precision", c.Precision());
  put("misses", static_cast<double>(c.misses));
  put("fragmentations", static_cast<double>(c.fragmentations));
  put("mostly_tracked", static_cast<double>(c.mostly_tracked));
  put("mostly_lost", static_cast<double>(c.mostly_lost));
  put("idf1", s.identity.Idf1());
  put("idp", s.identity.Idp());
  put("idr", s.identity.Idr());
  return v;
}

}  // namespace lookout::eval
