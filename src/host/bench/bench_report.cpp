// sslr-bench output: results.json (one record per run), results.csv, report/index.html (static:
// inline SVG plots of time against error with Pareto fronts, image strips, summary tables).
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <map>
#include <sstream>
#include <tuple>

#include "sslr_host/benchmark.hpp"
#include "sslr_host/image_io.hpp"

namespace sslr::host {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

json settingsJson(const BenchConfig& c) {
  const Settings& s = c.settings;
  if (c.method == "position-buffer")
    return {{"maxDistance", s.positionBuffer.maxDistance},
            {"resolution", s.positionBuffer.resolution},
            {"steps", s.positionBuffer.steps},
            {"thickness", s.positionBuffer.hitTolerance}};
  if (c.method == "dda")
    return {{"stride", s.dda.stride},     {"thickness", s.dda.objectDepth}, {"maxSteps", s.dda.maxSteps},
            {"maxDistance", s.dda.maxDistance}, {"jitter", s.dda.jitter},   {"refine", s.dda.refine}};
  if (c.method == "ffx-sssr")
    return {{"depthBufferThickness", s.ffx.depthBufferThickness},
            {"maxTraversalIntersections", s.ffx.maxTraversalIntersections}};
  if (c.method == "baseline") return json::object();
  const char* traversalPass = c.traversalPass == TraversalPass::Auto     ? "auto"
                              : c.traversalPass == TraversalPass::Inline ? "inline"
                                                                         : "deferred";
  return {{"adaptiveL.maxIterations", s.adaptiveL.maxIterations},
          {"traversal.maxSteps", s.traversal.maxSteps},
          {"traversalPass", traversalPass},         {"traversal.objectDepthRelative", s.traversal.objectDepthRelative},
          {"backDepth", c.backDepth},
          {"device", c.device == DeviceProfile::Gpu ? "gpu" : c.device == DeviceProfile::Software ? "software" : "auto"},
          {"traversal.hiddenGuess", s.traversal.hiddenGuess},
          {"oneBodyTraversal", c.oneBodyTraversal},
          {"occupancyExit", c.occupancyExit},
          {"adaptiveL.convergenceEps", s.adaptiveL.convergenceEps},
          {"adaptiveL.initialLengthScreen", s.adaptiveL.initialLengthScreen}, 
          {"blur.maxRadiusPx", s.blur.maxRadiusPx},
          {"selection.roughnessCutoff", s.selection.roughnessCutoff},   {"fresnel", s.fresnel == FresnelMode::Classic ? "classic" : "schlick"}};
}

// NaN/Inf are not JSON: write null for "not applicable".
json num(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }

// The composite error's breakdown (CompositeBreakdown): each kind's pixels, RMSE (null without
// pixels) and share.
json breakdownJson(const CompositeBreakdown& b) {
  auto kind = [](const CompositeBreakdown::Kind& k) {
    return json{{"pixels", k.pixels}, {"rmse", k.pixels > 0 ? num(k.rmse) : json(nullptr)}, {"share", num(k.share)}};
  };
  const CompositeBreakdown::ByTruth& t = b.byTruth;
  return {{"hit", kind(b.hit)},
          {"wrong", kind(b.wrong)},
          {"guessed", kind(b.guessed)},
          {"missed", kind(b.missed)},
          {"unreachable", kind(b.unreachable)},
          {"wrongAsMisses", kind(b.wrongAsMisses)},
          {"byTruth",
           {{"visible", kind(t.visible)},
            {"occluded", kind(t.occluded)},
            {"offScreen", kind(t.offScreen)},
            {"escaped", kind(t.escaped)}}}};
}

// Its CSV columns: the five kinds' shares, the wrong hits' RMSE and theirs as misses, then the
// shares by where the true reflection lies (empty where not measured).
std::string breakdownCsv(const json& b) {
  if (b.is_null()) return ",,,,,,,,,,";
  auto v = [](const json& x) { return x.is_null() ? std::string() : x.dump(); };
  const json& t = b["byTruth"];
  return v(b["hit"]["share"]) + "," + v(b["wrong"]["share"]) + "," + v(b["guessed"]["share"]) + "," +
         v(b["missed"]["share"]) + "," +
         v(b["unreachable"]["share"]) + "," + v(b["wrong"]["rmse"]) + "," + v(b["wrongAsMisses"]["rmse"]) + "," +
         v(t["visible"]["share"]) + "," + v(t["occluded"]["share"]) + "," + v(t["offScreen"]["share"]) + "," +
         v(t["escaped"]["share"]);
}
json nums(const std::vector<double>& v) {
  json a = json::array();
  for (double x : v) a.push_back(num(x));
  return a;
}

// Each pass's commands and texture traffic (FrameStats' per-pass fields) of the scored frame.
json passesJson(const FrameStats& st) {
  const std::tuple<const char*, const PassCommands*, const PassTraffic*> passes[] = {
      {"classify", &st.classifyCommands, &st.classifyTraffic}, {"pyramid", &st.pyramidCommands, &st.pyramidTraffic},
      {"trace", &st.traceCommands, &st.traceTraffic},          {"blur", &st.blurCommands, &st.blurTraffic},
      {"temporal", &st.temporalCommands, &st.temporalTraffic}, {"finish", &st.finishCommands, nullptr}};
  json out = json::array();
  for (const auto& [name, c, t] : passes) {
    const PassTraffic traffic = t != nullptr ? *t : PassTraffic{};
    out.push_back({{"pass", name},
                   {"dispatches", c->dispatches},
                   {"indirectDispatches", c->indirectDispatches},
                   {"barriers", c->barriers},
                   {"programs", c->programs},
                   {"uploads", c->uploads},
                   {"texelsRead", traffic.texelsRead},
                   {"texelsWritten", traffic.texelsWritten},
                   {"bytesRead", traffic.bytesRead},
                   {"bytesWritten", traffic.bytesWritten}});
  }
  return out;
}

// The trace dispatches' ray work (FrameStats::RayWork) of the scored frame: the frame's, and each
// dispatch that ran.
json rayWorkJson(const FrameStats& st) {
  auto one = [](const RayWork& w) {
    return json{{"laneSteps", w.laneSteps}, {"simt32", w.simt32}, {"simt64", w.simt64},
                {"longestChain", w.longestChain}, {"groups", w.groups}};
  };
  json out = one(st.totalRayWork());
  out["stepsPerTracedPixel"] = st.tracedPixels ? num(double(st.totalRayWork().laneSteps) / st.tracedPixels) : json(nullptr);
  json dispatches = json::object();
  const std::pair<const char*, const RayWork*> each[] = {
      {"trace", &st.traceWork}, {"retrace", &st.retraceWork}, {"quads", &st.quadWork}, {"quadRetrace", &st.quadRetraceWork}};
  for (const auto& [name, w] : each)
    if (w->groups > 0) dispatches[name] = one(*w);
  out["dispatches"] = dispatches;
  return out;
}

json runJson(const RunRecord& r) {
  const HitMetrics& m = r.metrics;
  const bool traced = r.method != "baseline";
  return {{"scene", r.scene},
          {"method", r.method},
          {"label", r.label},
          {"default", r.config.isDefault},
          {"parameters", settingsJson(r.config)},
          {"width", r.width},
          {"height", r.height},
          {"renderer", r.renderer},
          {"timingMethod", r.timingMethod},
          {"timeMedianMs", num(r.timeMedianMs)},
          {"timeMinMs", num(r.timeMinMs)},
          {"timeMaxMs", num(r.timeMaxMs)},
          {"frames", r.frames},
          {"classes", {{"visible", m.visible}, {"occluded", m.occluded}, {"offScreen", m.offScreen}, {"escaped", m.escaped},
                       {"visibleUnshown", m.unshown}}},
          {"recall1px", traced ? num(m.recall1px) : json(nullptr)},
          {"recall1pxShown", traced ? num(m.recallShown1px) : json(nullptr)},
          {"recall2px", traced ? num(m.recall2px) : json(nullptr)},
          {"recall4px", traced ? num(m.recall4px) : json(nullptr)},
          {"medianErrorPx", traced ? num(m.medianErrorPx) : json(nullptr)},
          {"p95ErrorPx", traced ? num(m.p95ErrorPx) : json(nullptr)},
          {"falseHitRate", traced ? num(m.falseHitRate) : json(nullptr)},
          {"reflectionRmse", traced ? num(m.reflectionRmse) : json(nullptr)},
          {"reflectionPsnr", traced ? num(m.reflectionPsnr) : json(nullptr)},
          {"compositeRmse", traced ? num(r.compositeRmse) : json(nullptr)},
          {"compositePsnr", traced ? num(r.compositePsnr) : json(nullptr)},
          {"compositeBreakdown", traced ? breakdownJson(r.compositeBreakdown) : json(nullptr)},
          {"predictedH100Ms", num(r.predictedH100Ms)},
          {"nonFiniteHitPixels", m.nonFinite},
          {"nonFiniteOutputPixels", r.nonFiniteOutputs},
          {"tracedPixels", r.tracedPixels},
          {"fetches", r.fetches},
          {"fetchesPerTracedPixel", traced ? num(r.fetchesPerTracedPixel) : json(nullptr)},
          {"dispatches", r.commands.dispatches},
          {"indirectDispatches", r.commands.indirectDispatches},
          {"barriers", r.commands.barriers},
          {"programs", r.commands.programs},
          {"bytesRead", r.traffic.bytesRead},
          {"bytesWritten", r.traffic.bytesWritten},
          {"passes", passesJson(r.frameStats)},
          {"rayWork", rayWorkJson(r.frameStats)},
          {"gbufferBytesPerPixel", r.gbufferBytesPerPixel},
          {"extraBytesPerPixel", r.extraBytesPerPixel}};
}

std::string fmt(double v, int precision = 3) {
  if (!std::isfinite(v)) return "–";
  std::ostringstream s;
  s.setf(std::ios::fixed);
  s.precision(precision);
  s << v;
  return s.str();
}

std::string esc(const std::string& t) {
  std::string o;
  for (char c : t) o += c == '<' ? "&lt;" : c == '>' ? "&gt;" : c == '&' ? "&amp;" : std::string(1, c);
  return o;
}

// Runs not dominated in (time, error): nothing is both faster and more accurate.
std::vector<const RunRecord*> pareto(std::vector<const RunRecord*> runs) {
  std::sort(runs.begin(), runs.end(), [](auto* a, auto* b) { return a->timeMedianMs < b->timeMedianMs; });
  std::vector<const RunRecord*> front;
  double best = INFINITY;
  for (const RunRecord* r : runs)
    if (r->metrics.reflectionRmse < best) {
      front.push_back(r);
      best = r->metrics.reflectionRmse;
    }
  return front;
}

const std::map<std::string, std::string>& methodColors() {
  static const std::map<std::string, std::string> colors = {{"adaptive-l", "#1f77b4"}, {"position-buffer", "#ff7f0e"},
                                                            {"hiz", "#2ca02c"},        {"dda", "#9467bd"},
                                                            {"ffx-sssr", "#d62728"},   {"baseline", "#777777"}};
  return colors;
}

std::string plotSvg(const std::vector<const RunRecord*>& runs, double baselineMs) {
  const double W = 640, H = 360, L = 60, R = 20, T = 20, B = 50;
  double maxT = baselineMs, maxE = 0;
  for (auto* r : runs) {
    maxT = std::max(maxT, r->timeMedianMs);
    maxE = std::max(maxE, r->metrics.reflectionRmse);
  }
  maxT = maxT > 0 ? maxT * 1.1 : 1.0;
  maxE = maxE > 0 ? maxE * 1.15 : 1.0;
  auto X = [&](double t) { return L + (W - L - R) * t / maxT; };
  auto Y = [&](double e) { return H - B - (H - T - B) * e / maxE; };
  std::ostringstream s;
  s << "<svg xmlns='http://www.w3.org/2000/svg' width='" << W << "' height='" << H << "' font-family='sans-serif' font-size='11'>"
    << "<rect width='100%' height='100%' fill='white'/>"
    << "<line x1='" << L << "' y1='" << H - B << "' x2='" << W - R << "' y2='" << H - B << "' stroke='black'/>"
    << "<line x1='" << L << "' y1='" << T << "' x2='" << L << "' y2='" << H - B << "' stroke='black'/>";
  for (int i = 0; i <= 4; ++i) {
    const double t = maxT * i / 4, e = maxE * i / 4;
    s << "<text x='" << X(t) << "' y='" << H - B + 15 << "' text-anchor='middle'>" << fmt(t, 1) << "</text>"
      << "<text x='" << L - 5 << "' y='" << Y(e) + 4 << "' text-anchor='end'>" << fmt(e, 3) << "</text>";
  }
  s << "<text x='" << (L + W - R) / 2 << "' y='" << H - 12 << "' text-anchor='middle'>median time per frame (ms)</text>"
    << "<text transform='rotate(-90)' x='" << -(T + H - B) / 2 << "' y='14' text-anchor='middle'>reflection RMSE on visible reflections</text>";
  if (baselineMs > 0)
    s << "<line x1='" << X(baselineMs) << "' y1='" << T << "' x2='" << X(baselineMs) << "' y2='" << H - B
      << "' stroke='gray' stroke-dasharray='4 3'/><text x='" << X(baselineMs) + 3 << "' y='" << T + 10
      << "' fill='gray'>read+write baseline</text>";
  for (const auto& [method, color] : methodColors()) {
    if (method == "baseline") continue;
    std::vector<const RunRecord*> mine;
    for (auto* r : runs)
      if (r->method == method) mine.push_back(r);
    const auto front = pareto(mine);
    if (front.size() > 1) {
      s << "<polyline fill='none' stroke='" << color << "' stroke-width='1.5' points='";
      for (auto* r : front) s << X(r->timeMedianMs) << "," << Y(r->metrics.reflectionRmse) << " ";
      s << "'/>";
    }
    for (auto* r : mine)
      s << "<circle cx='" << X(r->timeMedianMs) << "' cy='" << Y(r->metrics.reflectionRmse) << "' r='"
        << (r->config.isDefault ? 6 : 4) << "' fill='" << color << "' fill-opacity='0.8'><title>" << esc(r->method) << " "
        << esc(r->label) << ": " << fmt(r->timeMedianMs, 2) << " ms, RMSE " << fmt(r->metrics.reflectionRmse, 4)
        << ", recall@1px " << fmt(r->metrics.recall1px, 3) << "</title></circle>";
  }
  s << "<circle cx='" << W - 170 << "' cy='" << T + 30 << "' r='5' fill='#1f77b4'/><text x='" << W - 160 << "' y='" << T + 34
    << "'>adaptive-l (depth-only)</text><circle cx='" << W - 170 << "' cy='" << T + 48 << "' r='5' fill='#ff7f0e'/><text x='"
    << W - 160 << "' y='" << T + 52 << "'>position-buffer</text><circle cx='" << W - 170 << "' cy='" << T + 66
    << "' r='5' fill='#2ca02c'/><text x='" << W - 160 << "' y='" << T + 70 << "'>hiz (pyramid alone)</text><circle cx='"
    << W - 170 << "' cy='" << T + 84 << "' r='5' fill='#9467bd'/><text x='" << W - 160 << "' y='" << T + 88
    << "'>dda (McGuire-Mara)</text><circle cx='" << W - 170 << "' cy='" << T + 102 << "' r='5' fill='#d62728'/><text x='"
    << W - 160 << "' y='" << T + 106 << "'>ffx-sssr (FidelityFX SSSR)</text></svg>";
  return s.str();
}

// An SVG of W x H on white with its two axes (margins: left, right, top, bottom); the caller closes it.
std::string svgFrame(double W, double H, double L, double R, double T, double B) {
  std::ostringstream s;
  s << "<svg xmlns='http://www.w3.org/2000/svg' width='" << W << "' height='" << H
    << "' font-family='sans-serif' font-size='11'><rect width='100%' height='100%' fill='white'/>"
    << "<line x1='" << L << "' y1='" << H - B << "' x2='" << W - R << "' y2='" << H - B << "' stroke='black'/>"
    << "<line x1='" << L << "' y1='" << T << "' x2='" << L << "' y2='" << H - B << "' stroke='black'/>";
  return s.str();
}

// A cost curve: median time per method against pixels (log axis) or reflective fraction (%).
std::string curveSvg(const std::vector<CurvePoint>& points, const std::string& curve) {
  const double W = 640, H = 360, L = 60, R = 150, T = 20, B = 50;
  const bool byResolution = curve == "resolution";
  auto xValue = [&](const CurvePoint& p) {
    return byResolution ? std::log2(double(p.width) * p.height) : double(p.percent);
  };
  double xMin = INFINITY, xMax = -INFINITY, maxT = 0;
  for (const CurvePoint& p : points) {
    if (p.curve != curve) continue;
    xMin = std::min(xMin, xValue(p));
    xMax = std::max(xMax, xValue(p));
    maxT = std::max(maxT, p.timeMedianMs);
  }
  if (!(xMax > xMin)) xMax = xMin + 1;
  maxT = maxT > 0 ? maxT * 1.1 : 1.0;
  auto X = [&](double x) { return L + (W - L - R) * (x - xMin) / (xMax - xMin); };
  auto Y = [&](double t) { return H - B - (H - T - B) * t / maxT; };
  std::ostringstream s;
  s << svgFrame(W, H, L, R, T, B);
  for (int i = 0; i <= 4; ++i)
    s << "<text x='" << L - 5 << "' y='" << Y(maxT * i / 4) + 4 << "' text-anchor='end'>" << fmt(maxT * i / 4, 1)
      << "</text>";
  std::map<std::string, std::vector<const CurvePoint*>> byMethod;
  for (const CurvePoint& p : points)
    if (p.curve == curve) byMethod[p.method].push_back(&p);
  // x labels from one method's points (all methods share them).
  if (!byMethod.empty())
    for (const CurvePoint* p : byMethod.begin()->second)
      s << "<text x='" << X(xValue(*p)) << "' y='" << H - B + 15 << "' text-anchor='middle'>"
        << (byResolution ? std::to_string(p->width) + "x" + std::to_string(p->height) : std::to_string(p->percent) + "%")
        << "</text>";
  s << "<text x='" << (L + W - R) / 2 << "' y='" << H - 12 << "' text-anchor='middle'>"
    << (byResolution ? "resolution (mirror-room; log pixels)" : "reflective share of the frame (reflective-N scenes)")
    << "</text><text transform='rotate(-90)' x='" << -(T + H - B) / 2
    << "' y='14' text-anchor='middle'>median time per frame (ms)</text>";
  int legend = 0;
  for (const auto& [method, pts] : byMethod) {
    const auto it = methodColors().find(method);
    const std::string color = it == methodColors().end() ? "#000000" : it->second;
    s << "<polyline fill='none' stroke='" << color << "' stroke-width='1.5'"
      << (method == "baseline" ? " stroke-dasharray='4 3'" : "") << " points='";
    for (const CurvePoint* p : pts) s << X(xValue(*p)) << "," << Y(p->timeMedianMs) << " ";
    s << "'/>";
    for (const CurvePoint* p : pts)
      s << "<circle cx='" << X(xValue(*p)) << "' cy='" << Y(p->timeMedianMs) << "' r='3' fill='" << color
        << "'><title>" << esc(method) << ": " << fmt(p->timeMedianMs, 2) << " ms</title></circle>";
    s << "<line x1='" << W - R + 10 << "' y1='" << T + 10 + 16 * legend << "' x2='" << W - R + 30 << "' y2='"
      << T + 10 + 16 * legend << "' stroke='" << color << "' stroke-width='2'/><text x='" << W - R + 35 << "' y='"
      << T + 14 + 16 * legend << "'>" << esc(method) << "</text>";
    ++legend;
  }
  s << "</svg>";
  return s.str();
}

// The glossy study on one scene: relative RMSE against time, a point per configuration.
std::string glossySvg(const std::vector<const GlossyPoint*>& points) {
  const double W = 640, H = 300, L = 60, R = 170, T = 20, B = 50;
  double maxT = 0, maxE = 0;
  for (const GlossyPoint* p : points) {
    maxT = std::max(maxT, p->timeMedianMs);
    maxE = std::max(maxE, p->relativeRmse);
  }
  maxT = maxT > 0 ? maxT * 1.15 : 1.0;
  maxE = maxE > 0 ? maxE * 1.15 : 1.0;
  auto X = [&](double t) { return L + (W - L - R) * t / maxT; };
  auto Y = [&](double e) { return H - B - (H - T - B) * e / maxE; };
  static const char* colors[] = {"#1f77b4", "#2ca02c", "#9467bd", "#ff7f0e", "#d62728", "#8c564b"};
  std::ostringstream s;
  s << svgFrame(W, H, L, R, T, B);
  for (int i = 0; i <= 4; ++i)
    s << "<text x='" << X(maxT * i / 4) << "' y='" << H - B + 15 << "' text-anchor='middle'>" << fmt(maxT * i / 4, 1)
      << "</text><text x='" << L - 5 << "' y='" << Y(maxE * i / 4) + 4 << "' text-anchor='end'>" << fmt(maxE * i / 4, 2)
      << "</text>";
  s << "<text x='" << (L + W - R) / 2 << "' y='" << H - 12 << "' text-anchor='middle'>median dispatch time (ms)</text>"
    << "<text transform='rotate(-90)' x='" << -(T + H - B) / 2
    << "' y='14' text-anchor='middle'>relative RMSE against the GGX reference</text>";
  for (size_t i = 0; i < points.size(); ++i) {
    const char* color = colors[i % std::size(colors)];
    s << "<circle cx='" << X(points[i]->timeMedianMs) << "' cy='" << Y(points[i]->relativeRmse) << "' r='5' fill='"
      << color << "'><title>" << esc(points[i]->config) << ": " << fmt(points[i]->timeMedianMs, 2) << " ms, "
      << fmt(points[i]->relativeRmse, 3) << "</title></circle><circle cx='" << W - R + 15 << "' cy='" << T + 10 + 16 * i
      << "' r='5' fill='" << color << "'/><text x='" << W - R + 25 << "' y='" << T + 14 + 16 * i << "'>"
      << esc(points[i]->config) << "</text>";
  }
  s << "</svg>";
  return s.str();
}

// results.json: the options, every run, the scenes' classes and representations, the studies.
json resultsJson(const BenchResult& result) {
  json j;
  j["renderer"] = result.renderer;
  j["timingMethod"] = result.timingMethod;
  j["grid"] = result.options.grid;
  j["width"] = result.options.width;
  j["height"] = result.options.height;
  j["frames"] = result.options.frames;
  j["warmup"] = result.options.warmup;
  j["runs"] = json::array();
  for (const RunRecord& r : result.runs) j["runs"].push_back(runJson(r));
  j["scenes"] = json::array();
  for (const SceneRecord& s : result.scenes)
    j["scenes"].push_back({{"scene", s.scene},
                           {"reflectivePixels", s.reflective},
                           {"classes", {{"visible", s.visible}, {"occluded", s.occluded}, {"offScreen", s.offScreen}, {"escaped", s.escaped}}},
                           {"positionErrorMedian", num(s.positionErrorMedian)},
                           {"positionErrorMax", num(s.positionErrorMax)},
                           {"positionErrorMaxRelative", num(s.positionErrorMaxRelative)},
                           {"hitAgreementDepthVsStored", num(s.hitAgreement)},
                           {"recall1pxDepth", num(s.recallDepth)},
                           {"recall1pxStored", num(s.recallStored)},
                           {"showsNothing", s.showsNothing}});
  j["costCurves"] = json::array();
  for (const CurvePoint& p : result.curves)
    j["costCurves"].push_back({{"curve", p.curve},
                               {"method", p.method},
                               {"width", p.width},
                               {"height", p.height},
                               {"reflectivePercent", p.percent},
                               {"tracedFraction", num(p.tracedFraction)},
                               {"timeMedianMs", num(p.timeMedianMs)}});
  j["temporal"] = json::array();
  for (const TemporalPoint& p : result.temporal)
    j["temporal"].push_back({{"scene", p.scene},
                             {"config", p.config},
                             {"segment", p.segment},
                             {"frame", p.frame},
                             {"rmse", num(p.rmse)},
                             {"rmseVisible", num(p.rmseVisible)},
                             {"rmseHidden", num(p.rmseHidden)},
                             {"dispatchMs", num(p.dispatchMs)}});
  j["views"] = json::array();
  for (const ViewsPoint& p : result.views)
    j["views"].push_back({{"scene", p.scene},
                          {"config", p.config},
                          {"views", p.views},
                          {"width", result.options.viewsWidth},
                          {"height", result.options.viewsHeight},
                          {"timeMedianMs", num(p.timeMedianMs)},
                          {"ratioToOneView", num(p.ratioToOneView)},
                          {"dispatches", p.commands.dispatches},
                          {"indirectDispatches", p.commands.indirectDispatches},
                          {"barriers", p.commands.barriers},
                          {"programs", p.commands.programs},
                          {"uploads", p.commands.uploads},
                          {"tracedPixels", p.tracedPixels},
                          {"tiles", p.tiles}});
  j["glossy"] = json::array();
  for (const GlossyPoint& p : result.glossy)
    j["glossy"].push_back({{"scene", p.scene},
                           {"config", p.config},
                           {"rmse", num(p.rmse)},
                           {"relativeRmse", num(p.relativeRmse)},
                           {"uncovered", num(p.uncovered)},
                           {"referenceNoise", num(p.referenceNoise)},
                           {"rmseAboveNoise", num(p.rmseAboveNoise)},
                           {"displayRmse", num(p.displayRmse)},
                           {"scored", p.scored},
                           {"frames", p.rmseByFrame.size()},
                           {"rmseByFrame", nums(p.rmseByFrame)},
                           {"timeMedianMs", num(p.timeMedianMs)}});
  return j;
}

// results.csv: one row per run.
std::string resultsCsv(const BenchResult& result) {
  std::ostringstream out;
  out << "scene,method,label,default,width,height,renderer,timingMethod,timeMedianMs,timeMinMs,timeMaxMs,frames,"
         "visible,occluded,offScreen,escaped,recall1px,recall2px,recall4px,medianErrorPx,p95ErrorPx,falseHitRate,"
         "reflectionRmse,reflectionPsnr,nonFiniteHitPixels,nonFiniteOutputPixels,tracedPixels,fetches,"
         "fetchesPerTracedPixel,dispatches,indirectDispatches,barriers,programs,bytesRead,bytesWritten,laneSteps,simt32,"
         "simt64,longestChain,gbufferBytesPerPixel,extraBytesPerPixel,compositeRmse,compositePsnr,predictedH100Ms,"
         "compositeHitShare,compositeWrongShare,compositeGuessedShare,compositeMissedShare,compositeUnreachableShare,compositeWrongRmse,"
         "compositeWrongAsMissesRmse,compositeVisibleShare,compositeOccludedShare,compositeOffScreenShare,"
         "compositeEscapedShare,parameters\n";
  for (const RunRecord& r : result.runs) {
    const json rj = runJson(r);
    const RayWork work = r.frameStats.totalRayWork();
    auto v = [&](const char* k) { return rj[k].is_null() ? std::string() : rj[k].dump(); };
    std::string params = rj["parameters"].dump();
    std::string quoted = "\"";
    for (char c : params) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
    quoted += "\"";
    out << r.scene << "," << r.method << ",\"" << r.label << "\"," << (r.config.isDefault ? 1 : 0) << "," << r.width
        << "," << r.height << ",\"" << r.renderer << "\",\"" << r.timingMethod << "\"," << v("timeMedianMs") << ","
        << v("timeMinMs") << "," << v("timeMaxMs") << "," << r.frames << "," << r.metrics.visible << ","
        << r.metrics.occluded << "," << r.metrics.offScreen << "," << r.metrics.escaped << "," << v("recall1px") << ","
        << v("recall2px") << "," << v("recall4px") << "," << v("medianErrorPx") << "," << v("p95ErrorPx") << ","
        << v("falseHitRate") << "," << v("reflectionRmse") << "," << v("reflectionPsnr") << "," << r.metrics.nonFinite
        << "," << r.nonFiniteOutputs << "," << r.tracedPixels << "," << r.fetches << "," << v("fetchesPerTracedPixel")
        << "," << r.commands.dispatches << "," << r.commands.indirectDispatches << "," << r.commands.barriers << ","
        << r.commands.programs << "," << r.traffic.bytesRead << "," << r.traffic.bytesWritten << ","
        << work.laneSteps << "," << work.simt32 << "," << work.simt64 << "," << work.longestChain
        << "," << r.gbufferBytesPerPixel << "," << r.extraBytesPerPixel << "," << v("compositeRmse") << ","
        << v("compositePsnr") << "," << v("predictedH100Ms") << "," << breakdownCsv(rj["compositeBreakdown"]) << ","
        << quoted << "\n";
  }
  return out.str();
}

// The report's head: how the runs were timed and scored.
void reportHead(std::ostringstream& h, const BenchResult& result) {
  h << "<!doctype html><html><head><meta charset='utf-8'><title>sslr benchmark</title><style>"
       "body{font-family:sans-serif;margin:24px;max-width:1400px}table{border-collapse:collapse;margin:8px 0 24px}"
       "td,th{border:1px solid #ccc;padding:3px 8px;text-align:right}th{background:#f3f3f3}td:first-child,th:first-child"
       "{text-align:left}.strip img{width:320px;image-rendering:pixelated;margin-right:6px}.strip figure{display:inline-block;"
       "margin:0 8px 8px 0}.good{color:#080}.bad{color:#b00}</style></head><body>"
    << "<h1>sslr: run time against error</h1><p>Renderer: <b>" << esc(result.renderer) << "</b>. Timing: <b>"
    << esc(result.timingMethod) << "</b>, median of " << result.options.frames << " frames after " << result.options.warmup
    << " warm-up, all configurations interleaved in one run (compare them as ratios). Grid: " << esc(result.options.grid)
    << ", " << result.options.width << "x" << result.options.height
    << ". Error: Embree ground truth; recall = visible (class A) reflections reported (confidence &gt; 0.5) within N px of "
       "the true hit; false hits = occluded/off-screen/escaped reflections reported; RMSE = colour at the reported hit "
       "(0 if none) vs colour at the true hit, over class A; composite RMSE = the final image (the reflection "
       "composited over the fallback) against a ray-traced reference composite, over the mirror pixels, and the share "
       "of its squared error in hits within 1 px, wrong hits, guesses below the reporting threshold, misses and "
       "reflections no screen-space method sees, "
       "then by where the true reflection lies (on the screen, a hidden side, off the screen, escaped); "
       "wrong hits as misses = those pixels' RMSE, then as if nothing had been reported there. Large dots: "
       "each method's default.</p>";
}

// Kinds' shares of a run's squared composite error, "a / b / ... %", empty where not measured.
std::string sharesCell(const RunRecord& r, std::initializer_list<const CompositeBreakdown::Kind*> kinds) {
  if (!std::isfinite(r.compositeRmse)) return "";
  std::string cell;
  for (const CompositeBreakdown::Kind* k : kinds) cell += (cell.empty() ? "" : " / ") + fmt(100.0 * k->share, 0);
  return cell + "%";
}
// By kind: hits within 1 px / wrong / guessed / missed / unreachable.
std::string breakdownCell(const RunRecord& r) {
  const CompositeBreakdown& b = r.compositeBreakdown;
  return sharesCell(r, {&b.hit, &b.wrong, &b.guessed, &b.missed, &b.unreachable});
}
// By where the true reflection lies: on the screen / a hidden side / off the screen / escaped.
std::string byTruthCell(const RunRecord& r) {
  const CompositeBreakdown::ByTruth& t = r.compositeBreakdown.byTruth;
  return sharesCell(r, {&t.visible, &t.occluded, &t.offScreen, &t.escaped});
}
// Its wrong hits' RMSE, then the same pixels' as misses (lower: a miss would have served them better).
std::string wrongAsMissesCell(const RunRecord& r) {
  const CompositeBreakdown& b = r.compositeBreakdown;
  if (!std::isfinite(r.compositeRmse) || b.wrong.pixels == 0) return "";
  return fmt(b.wrong.rmse, 3) + " &rarr; " + fmt(b.wrongAsMisses.rmse, 3);
}

// The defaults side by side per scene, and each method's fastest configuration reaching recall 0.95.
void reportSummaries(std::ostringstream& h, const BenchResult& result) {
  // Summary table: the defaults side by side per scene.
  h << "<h2>Summary (defaults)</h2><table><tr><th>scene</th><th>method</th><th>time ms</th><th>time ratio</th>"
       "<th>recall@1px</th><th>p95 px</th><th>false hits</th><th>RMSE</th><th>composite RMSE</th>"
       "<th>its error: hits / wrong / guessed / missed / unreachable</th><th>by the truth: on screen / hidden side / off "
       "screen / escaped</th><th>wrong hits as misses</th><th>fetches/px</th><th>G-buffer B/px</th></tr>";
  for (const SceneRecord& sc : result.scenes) {
    // Each method's default; the time ratio is to the tutorial's configuration.
    const SceneDefaults defaults = defaultRuns(result, sc.scene);
    const RunRecord* p = defaults.tutorial;
    for (const RunRecord* r : defaults.runs) {
      const double ratio = (p && p->timeMedianMs > 0) ? r->timeMedianMs / p->timeMedianMs : NAN;
      h << "<tr><td>" << esc(sc.scene) << "</td><td>" << esc(r->method) << " " << esc(r->label) << "</td><td>"
        << fmt(r->timeMedianMs, 2) << "</td><td>" << fmt(ratio, 2) << "</td><td>" << fmt(r->metrics.recall1px, 4)
        << "</td><td>" << fmt(r->metrics.p95ErrorPx, 3) << "</td><td>" << fmt(r->metrics.falseHitRate, 4) << "</td><td>"
        << fmt(r->metrics.reflectionRmse, 4) << "</td><td>" << fmt(r->compositeRmse, 4) << "</td><td>"
        << breakdownCell(*r) << "</td><td>" << byTruthCell(*r) << "</td><td>" << wrongAsMissesCell(*r) << "</td><td>"
        << fmt(r->fetchesPerTracedPixel, 1) << "</td><td>"
        << r->gbufferBytesPerPixel << "</td></tr>";
    }
  }
  h << "</table>";
  // Each method at its best: the fastest configuration that reaches recall 0.95.
  h << "<h2>Fastest configuration reaching recall@1px &ge; " << fmt(kParetoRecall, 2)
    << "</h2><p>Per scene and method, over the whole grid; time ratio to adaptive-l's fastest such "
       "configuration (&gt; 1: slower than sslr's).</p><table><tr><th>scene</th><th>method</th><th>config</th>"
       "<th>time ms</th><th>ratio to adaptive-l</th><th>recall@1px</th><th>false hits</th></tr>";
  for (const SceneRecord& sc : result.scenes) {
    const auto fastest = fastestReaching(result, sc.scene, kParetoRecall);
    const RunRecord* ours = nullptr;
    for (const FastestRun& f : fastest)
      if (f.method == "adaptive-l") ours = f.run;
    for (const FastestRun& f : fastest) {
      h << "<tr><td>" << esc(sc.scene) << "</td><td>" << esc(f.method) << "</td>";
      if (!f.run) {
        h << "<td>none reaches it</td><td colspan='4'></td></tr>";
        continue;
      }
      const double ratio = ours && ours->timeMedianMs > 0 ? f.run->timeMedianMs / ours->timeMedianMs : NAN;
      h << "<td>" << esc(f.run->label) << "</td><td>" << fmt(f.run->timeMedianMs, 2) << "</td><td>" << fmt(ratio, 2)
        << "</td><td>" << fmt(f.run->metrics.recall1px, 4) << "</td><td>" << fmt(f.run->metrics.falseHitRate, 4)
        << "</td></tr>";
    }
  }
  h << "</table>";
}

// Cost curves, with the ratios the targets are stated in (their SVGs also as files).
Status reportCurves(std::ostringstream& h, const BenchResult& result, const std::string& outDir) {
  // Cost curves, with the ratios the targets are stated in.
  for (const char* curve : {"resolution", "fraction"}) {
    bool any = false;
    for (const CurvePoint& p : result.curves) any = any || p.curve == curve;
    if (!any) continue;
    const std::string svg = curveSvg(result.curves, curve);
    if (Status s = writeTextFile((fs::path(outDir) / "report" / (std::string("curve-") + curve + ".svg")).string(), svg + "\n"); !s)
      return s;
    h << "<h2>Cost against " << (std::string(curve) == "resolution" ? "resolution" : "reflective fraction")
      << "</h2>" << svg << "<table><tr><th>point</th><th>traced share</th>";
    std::vector<std::string> methods;
    for (const CurvePoint& p : result.curves)
      if (p.curve == curve && std::find(methods.begin(), methods.end(), p.method) == methods.end())
        methods.push_back(p.method);
    for (const std::string& m : methods) h << "<th>" << esc(m) << " ms</th>";
    h << "<th>adaptive-l / baseline</th></tr>";
    for (size_t i = 0; i < result.curves.size(); i += methods.size()) {
      const CurvePoint& first = result.curves[i];
      if (first.curve != curve) continue;
      double ours = NAN, base = NAN;
      h << "<tr><td>"
        << (first.percent >= 0 ? "reflective-" + std::to_string(first.percent)
                               : std::to_string(first.width) + "x" + std::to_string(first.height))
        << "</td><td>" << fmt(first.tracedFraction, 4) << "</td>";
      for (size_t k = i; k < i + methods.size() && k < result.curves.size(); ++k) {
        h << "<td>" << fmt(result.curves[k].timeMedianMs, 2) << "</td>";
        if (result.curves[k].method == "adaptive-l") ours = result.curves[k].timeMedianMs;
        if (result.curves[k].method == "baseline") base = result.curves[k].timeMedianMs;
      }
      h << "<td>" << fmt(ours / base, 2) << "</td></tr>";
    }
    h << "</table>";
  }
  return Status{};
}

// The temporal, views and glossy studies (the glossy plots also as files).
Status reportStudies(std::ostringstream& h, const BenchResult& result, const std::string& outDir) {
  // Several views: one context of every view against a context a view and one view alone.
  if (!result.views.empty()) {
    h << "<h2>Several views in the same dispatches</h2><p>" << result.options.viewsCount
      << " eyes 0.064 units apart, " << result.options.viewsWidth << "x" << result.options.viewsHeight
      << ", the default settings: eye 0 alone, every eye by a context of its own, and every eye by one context of "
         "every view (ContextDesc::views, 2D-array G-buffers). Time: a frame of every eye the configuration traces, "
         "median, configurations interleaved in alternating order; ratio to one view: the median of each round's. Commands: one frame's, every context's summed "
         "(uploads include the stats ring's three).</p>"
      << "<table><tr><th>scene</th><th>configuration</th><th>ms</th><th>ratio</th><th>dispatches</th>"
         "<th>indirect</th><th>barriers</th><th>programs</th><th>uploads</th><th>traced px</th></tr>";
    for (const ViewsPoint& p : result.views) {
      h << "<tr><td>" << esc(p.scene) << "</td><td>" << esc(p.config) << "</td><td>" << fmt(p.timeMedianMs, 2)
        << "</td><td>" << fmt(p.ratioToOneView, 2) << "&times;</td><td>" << p.commands.dispatches
        << "</td><td>" << p.commands.indirectDispatches << "</td><td>" << p.commands.barriers << "</td><td>"
        << p.commands.programs << "</td><td>" << p.commands.uploads << "</td><td>" << p.tracedPixels << "</td></tr>";
    }
    h << "</table>";
  }
  // Temporal reuse over a camera path.
  if (!result.temporal.empty()) {
    h << "<h2>Temporal reuse over a camera path</h2><p>Still for 8 frames, then orbiting 0.25&deg; and 2.5&deg; "
         "per frame for 8 each, at "
      << result.options.temporalWidth << "x" << result.options.temporalHeight
      << ". Error: RMSE of the resolved reflection against the ideal one (Embree truth, confidence 1), over every "
         "reflective pixel, over those whose true reflection is visible (A) and over the others (B, C, D: ghosts "
         "and false hits); still = its last 4 frames. Time: median dispatch, one sample per frame.</p>"
      << "<table><tr><th>scene</th><th>configuration</th><th>segment</th><th>RMSE</th><th>RMSE A</th>"
         "<th>RMSE B-D</th><th>ms</th></tr>";
    for (const TemporalSummary& t : summarizeTemporal(result.temporal))
      h << "<tr><td>" << esc(t.scene) << "</td><td>" << esc(t.config) << "</td><td>" << t.segment << "</td><td>"
        << fmt(t.rmse, 4) << "</td><td>" << fmt(t.rmseVisible, 4) << "</td><td>" << fmt(t.rmseHidden, 4)
        << "</td><td>" << fmt(t.dispatchMs, 2) << "</td></tr>";
    h << "</table>";
  }
  // Glossy reflections against the GGX reference.
  if (!result.glossy.empty()) {
    h << "<h2>Glossy reflections against a GGX reference</h2><p>Radiance output (no Fresnel term): rgb / a against "
         "the GGX lobe's mean radiance gathered by Embree from what the screen shows ("
      << result.options.glossySamples << " rays a pixel, " << result.options.glossyWidth << "x"
      << result.options.glossyHeight << ", scored after " << result.options.glossyFrames
      << " still frames), over the pixels of roughness &ge; 0.1 whose lobe lies at least 90% on visible geometry. Reference noise: "
         "the reference's own RMS noise (half the difference of its two halves).</p>";
    std::vector<std::string> scenes;
    for (const GlossyPoint& p : result.glossy)
      if (std::find(scenes.begin(), scenes.end(), p.scene) == scenes.end()) scenes.push_back(p.scene);
    for (const std::string& scene : scenes) {
      std::vector<const GlossyPoint*> points;
      for (const GlossyPoint& p : result.glossy)
        if (p.scene == scene) points.push_back(&p);
      const std::string svg = glossySvg(points);
      if (Status st = writeTextFile((fs::path(outDir) / "report" / ("glossy-" + fileSlug(scene) + ".svg")).string(), svg + "\n"); !st)
        return st;
      h << "<h3>" << esc(scene) << "</h3>" << svg
        << "<table><tr><th>configuration</th><th>ms</th><th>RMSE</th><th>above the reference's noise</th>"
           "<th>relative RMSE</th><th>display RMSE</th><th>no estimate</th><th>scored px</th><th>reference noise</th></tr>";
      for (const GlossyPoint* p : points)
        h << "<tr><td>" << esc(p->config) << "</td><td>" << fmt(p->timeMedianMs, 2) << "</td><td>" << fmt(p->rmse, 4)
          << "</td><td>" << fmt(p->rmseAboveNoise, 4) << "</td><td>" << fmt(p->relativeRmse, 3) << "</td><td>"
          << fmt(p->displayRmse, 4) << "</td><td>"
          << fmt(p->uncovered, 3) << "</td><td>" << p->scored << "</td><td>" << fmt(p->referenceNoise, 4) << "</td></tr>";
      h << "</table><div class='strip'><figure><img src='" << fileSlug(scene) << "-glossy-truth.png'><figcaption>reference"
           "</figcaption></figure>";
      for (const GlossyPoint* p : points)
        h << "<figure><img src='" << fileSlug(scene) << "-glossy-" << fileSlug(p->config)
          << "-error.png'><figcaption>" << esc(p->config) << ": |error| x4 (blue: no estimate)</figcaption></figure>";
      h << "</div>";
    }
  }
  return Status{};
}

// Per scene: its plot (also as a file), images, representations and every run.
Status reportScenes(std::ostringstream& h, const BenchResult& result, const std::string& outDir) {
  for (const SceneRecord& sc : result.scenes) {
    std::vector<const RunRecord*> runs;
    double baselineMs = 0;
    for (const RunRecord& r : result.runs)
      if (r.scene == sc.scene) {
        if (r.method == "baseline") baselineMs = r.timeMedianMs;
        else runs.push_back(&r);
      }
    // Each plot also as a standalone SVG file (docs link to them).
    const std::string svg = plotSvg(runs, baselineMs);
    if (Status s = writeTextFile((fs::path(outDir) / "report" / ("plot-" + fileSlug(sc.scene) + ".svg")).string(), svg + "\n"); !s)
      return s;
    h << "<h2>" << esc(sc.scene) << "</h2><p>Reflective pixels " << sc.reflective << ": visible " << sc.visible
      << ", occluded " << sc.occluded << ", off screen " << sc.offScreen << ", escaped " << sc.escaped << ".</p>"
      << svg << "<div class='strip'>";
    for (const std::string& img : sc.images) h << "<figure><img src='" << esc(img) << "'><figcaption>" << esc(img) << "</figcaption></figure>";
    h << "</div><p>Error maps: black exact, green up to 1 px, yellow 2 px, red 4+ px, magenta visible but missed, "
         "white false hit. Representations alone (same adaptive-L tracer, CPU): position rebuilt from depth vs stored "
         "RGBA32F position: median error "
      << fmt(sc.positionErrorMedian, 7) << ", max " << fmt(sc.positionErrorMax, 6) << " view units (max relative "
      << fmt(sc.positionErrorMaxRelative, 7) << "); hit agreement " << fmt(sc.hitAgreement, 4) << "; recall@1px "
      << fmt(sc.recallDepth, 4) << " (depth) vs " << fmt(sc.recallStored, 4) << " (stored).</p>"
      << "<table><tr><th>method</th><th>config</th><th>time ms</th><th>recall@1/2/4px</th><th>median / p95 px</th>"
         "<th>false hits</th><th>RMSE / PSNR</th><th>fetches/px</th><th>NaN/Inf</th></tr>";
    for (const RunRecord* r : runs)
      h << "<tr><td>" << esc(r->method) << "</td><td>" << esc(r->label) << "</td><td>" << fmt(r->timeMedianMs, 2)
        << "</td><td>" << fmt(r->metrics.recall1px, 3) << " / " << fmt(r->metrics.recall2px, 3) << " / "
        << fmt(r->metrics.recall4px, 3) << "</td><td>" << fmt(r->metrics.medianErrorPx, 3) << " / "
        << fmt(r->metrics.p95ErrorPx, 3) << "</td><td>" << fmt(r->metrics.falseHitRate, 4) << "</td><td>"
        << fmt(r->metrics.reflectionRmse, 4) << " / " << fmt(r->metrics.reflectionPsnr, 1) << " dB</td><td>"
        << fmt(r->fetchesPerTracedPixel, 1) << "</td><td>" << r->metrics.nonFinite + r->nonFiniteOutputs << "</td></tr>";
    h << "<tr><td>baseline</td><td>read G-buffer + write 1 texel</td><td>" << fmt(baselineMs, 2)
      << "</td><td colspan='6'></td></tr></table>";
  }
  return Status{};
}

}  // namespace

Status writeBenchResults(const BenchResult& result, const std::string& outDir) {
  std::error_code ec;
  fs::create_directories(fs::path(outDir) / "report", ec);
  if (ec) return Status::error("cannot create " + outDir + "/report: " + ec.message());
  if (Status s = writeTextFile((fs::path(outDir) / "results.json").string(), resultsJson(result).dump(2) + "\n"); !s)
    return s;
  if (Status s = writeTextFile((fs::path(outDir) / "results.csv").string(), resultsCsv(result)); !s) return s;
  std::ostringstream h;
  reportHead(h, result);
  reportSummaries(h, result);
  if (Status s = reportCurves(h, result, outDir); !s) return s;
  if (Status s = reportStudies(h, result, outDir); !s) return s;
  if (Status s = reportScenes(h, result, outDir); !s) return s;
  h << "</body></html>\n";
  return writeTextFile((fs::path(outDir) / "report" / "index.html").string(), h.str());
}
}  // namespace sslr::host
