#include <bodyfmt/dynamics/scenario.h>

#include <bodyfmt/rules.h>
#include <bodyfmt/yaml.h>  // as the body files are read: the same bounded reader, dialect and positions

#include <fmt/format.h>

#include <cmath>
#include <set>

namespace bodyfmt::dynamics {
namespace {

class Reader : public YamlReader {
 public:
  Reader(const Model& model, DiagnosticSink& sink) : YamlReader(sink, "dynamics-scenario"), model_(model) {}

  void error_key(const YamlEntry& entry, std::string message) { error(entry.key_location, std::move(message)); }

  /// Checks that every key of `node` is one of `keys`.
  void keys(const YamlNode& node, const std::vector<std::string_view>& allowed) {
    std::string list;
    for (std::string_view k : allowed) list += (list.empty() ? "" : ", ") + std::string(k);
    for (const YamlEntry& entry : unknown_keys(node, allowed))
      error_key(entry, fmt::format("unknown key '{}' (keys: {})", entry.key, list));
  }

  LinkIndex link(const YamlEntry& entry, bool want_joint, bool want_track) {
    const LinkIndex index = model_.find_link(entry.key);
    if (index < 0) {
      error_key(entry, fmt::format("the model has no link \"{}\"", entry.key));
      return -1;
    }
    const JointType type = model_.links[index].joint_type;
    if (want_track && type != JointType::kPseudoContinuousTrack) {
      error_key(entry, fmt::format("link \"{}\" is not a pseudo_continuous_track", entry.key));
      return -1;
    }
    if (want_joint && type != JointType::kRevolute && type != JointType::kPrismatic) {
      error_key(entry, fmt::format("link \"{}\" has no revolute or prismatic joint", entry.key));
      return -1;
    }
    return index;
  }

 private:
  const Model& model_;
};

/// Passes every finding on and keeps where the YAML reader found a key repeated: in a scenario
/// that is an error, not a warning where the last value silently wins.
class DuplicateKeys : public DiagnosticSink {
 public:
  explicit DuplicateKeys(DiagnosticSink& inner) : inner_(inner) {}
  void report(Diagnostic d) override {
    if (d.rule_id == "yaml-duplicate-key") at.push_back(d.location);
    inner_.report(std::move(d));
  }
  std::vector<SourceLocation> at;

 private:
  DiagnosticSink& inner_;
};

}  // namespace

std::optional<ScenarioSpec> read_scenario(const std::string& path, const Model& model, DiagnosticSink& sink) {
  DuplicateKeys duplicates(sink);
  const std::optional<YamlDocument> document =
      read_yaml_file(path, duplicates, YamlLimits{}, "the scenario \"" + path + "\"");
  if (!document) return std::nullopt;
  Reader r(model, sink);
  for (const SourceLocation& at : duplicates.at)
    r.error(at, "a key repeated in a scenario is refused (which value was meant?)");
  std::vector<std::pair<double, SourceLocation>> times;
  ScenarioSpec spec;
  const YamlNode root = document->root();
  spec.at = root.location();
  if (!r.mapping(root, "a scenario")) return std::nullopt;
  r.keys(root, {"duration", "sample", "initial", "commands"});
  bool has_duration = false;
  for (const YamlEntry& entry : root.entries()) {
    const YamlNode& value = entry.value;
    if (entry.key == "duration" || entry.key == "sample") {
      if (std::optional<double> v = r.number(value, "'" + std::string(entry.key) + "'")) {
        if (!(*v > 0)) r.error(value, "'" + std::string(entry.key) + "' must be positive");
        (entry.key == "duration" ? spec.duration : spec.sample) = *v;
        (entry.key == "duration" ? spec.duration_at : spec.sample_at) = value.location();
        has_duration = has_duration || entry.key == "duration";
      }
    } else if (entry.key == "initial" && r.mapping(value, "'initial'")) {
      r.keys(value, {"on_floor", "position", "yaw", "joints"});
      for (const YamlEntry& e : value.entries()) {
        if (e.key == "on_floor") {
          std::optional<bool> b = r.boolean(e.value, "'on_floor'");
          spec.on_floor = b.value_or(false);
        } else if (e.key == "position") {
          if (!e.value.is_sequence() || e.value.items().size() != 3) {
            r.error(e.value, "'position' must be a list of three numbers (m)");
            continue;
          }
          Eigen::Vector3d p;
          for (int k = 0; k < 3; ++k) p[k] = r.number(e.value.items()[k], "a coordinate").value_or(0);
          spec.position = p;
        } else if (e.key == "yaw") {
          spec.yaw = r.number(e.value, "'yaw' (rad)");
        } else if (e.key == "joints" && r.mapping(e.value, "'joints'")) {
          for (const YamlEntry& j : e.value.entries()) {
            const LinkIndex link = r.link(j, true, false);
            if (std::optional<double> q = r.number(j.value, "a joint position (rad or m)"); q && link >= 0)
              spec.joints[link] = *q;
          }
        }
      }
    } else if (entry.key == "commands") {
      if (!value.is_sequence()) {
        r.error(value, "'commands' must be a list");
        continue;
      }
      double last = 0;
      std::set<LinkIndex> has_gain;  // a servo keeps its gains until a later command changes them
      for (const YamlNode& item : value.items()) {
        if (!r.mapping(item, "a command")) continue;
        r.keys(item, {"time", "tracks", "joints"});
        ScenarioCommand command;
        command.at = item.location();
        const std::optional<YamlEntry> time = item.find("time");
        if (!time) {
          r.error(item, "a command needs 'time' (s)");
        } else if (std::optional<double> t = r.number(time->value, "'time'")) {
          if (*t < 0)
            r.error(time->value, fmt::format("'time' {:g} s is negative: a scenario starts at 0 s", *t));
          else if (*t < last)
            r.error(time->value, "commands must be in time order");
          command.time = last = std::max(*t, last);
          times.emplace_back(*t, time->value.location());
        }
        if (const std::optional<YamlEntry> tracks = item.find("tracks");
            tracks && r.mapping(tracks->value, "'tracks'")) {
          for (const YamlEntry& t : tracks->value.entries()) {
            const LinkIndex link = r.link(t, false, true);
            if (std::optional<double> v = r.number(t.value, "a track speed (m/s)"); v && link >= 0)
              command.tracks[link] = *v;
          }
        }
        if (const std::optional<YamlEntry> joints = item.find("joints");
            joints && r.mapping(joints->value, "'joints'")) {
          for (const YamlEntry& j : joints->value.entries()) {
            const LinkIndex link = r.link(j, true, false);
            if (!r.mapping(j.value, "a joint command")) continue;
            r.keys(j.value, {"target", "p", "d", "torque"});
            ScenarioServo servo;
            for (const YamlEntry& field : j.value.entries()) {
              std::optional<double> v = r.number(field.value, "'" + std::string(field.key) + "'");
              if (field.key == "target") servo.target = v;
              if (field.key == "p") servo.p = v, servo.p_at = field.value.location();
              if (field.key == "d") servo.d = v, servo.d_at = field.value.location();
              if (field.key == "torque") servo.torque = v;
            }
            if (servo.p) has_gain.insert(link);
            if (servo.target && !has_gain.count(link))
              r.error(j.value, "a joint 'target' needs the gain 'p' (here or in an earlier command)");
            if (link >= 0) command.joints[link] = servo;
          }
        }
        spec.commands.push_back(std::move(command));
      }
    }
  }
  if (!has_duration) r.error(root, "a scenario needs 'duration' (s)");
  for (const auto& [t, at] : times)
    if (has_duration && t > spec.duration)
      r.error(at, fmt::format("a command at {:g} s comes after 'duration' ({:g} s) and would never take effect", t,
                              spec.duration));
  if (r.ok() && spec.duration / spec.sample > 1e7) r.error(root, "'duration' / 'sample' gives more than 1e7 rows");
  if (!r.ok()) return std::nullopt;
  return spec;
}

bool run_scenario(const Model& model, const Derived& derived, const ScenarioSpec& scenario, const SimOptions& options,
                  std::ostream& csv, DiagnosticSink& sink, RunStats* stats) {
  std::unique_ptr<Simulation> sim = Simulation::build(model, derived, options, sink);
  if (!sim) return false;
  const std::size_t n = model.links.size();
  // Initial state.
  Eigen::Isometry3d X = as_isometry(model.root().X_PL);
  if (scenario.position) X.translation() = *scenario.position;
  if (scenario.yaw) X.linear() = Eigen::AngleAxisd(*scenario.yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  for (const auto& [link, q] : scenario.joints) sim->set_joint_position(link, q);
  sim->set_root_pose(X);
  if (scenario.on_floor && !sim->contact_points().empty()) {
    X.translation().z() -= -sim->max_penetration();
    sim->set_root_pose(X);
  }
  // Which links touch the floor gets a column: those with contact points.
  std::set<LinkIndex> contact_links;
  for (const ContactPoint& p : sim->contact_points()) contact_links.insert(p.link);

  csv << "time,x,y,z,qw,qx,qy,qz,wx,wy,wz,vx,vy,vz";
  for (std::size_t i = 0; i < n; ++i)
    if (sim->has_joint(static_cast<LinkIndex>(i))) csv << ",q:" << model.links[i].name << ",dq:" << model.links[i].name;
  csv << ",contact_fx,contact_fy,contact_fz";
  for (LinkIndex link : contact_links) csv << ",fz:" << model.links[link].name;
  csv << "\n";
  auto row = [&] {
    const Eigen::Isometry3d pose = sim->link_pose(0);
    const Eigen::Quaterniond q(pose.linear());
    const auto [omega, v] = sim->link_velocity(0);
    std::string line =
        fmt::format("{:.6f},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g}",
                    sim->time(), pose.translation().x(), pose.translation().y(), pose.translation().z(), q.w(), q.x(),
                    q.y(), q.z(), omega.x(), omega.y(), omega.z(), v.x(), v.y(), v.z());
    for (std::size_t i = 0; i < n; ++i)
      if (sim->has_joint(static_cast<LinkIndex>(i)))
        line += fmt::format(",{:.9g},{:.9g}", sim->joint_position(static_cast<LinkIndex>(i)),
                            sim->joint_velocity(static_cast<LinkIndex>(i)));
    const Eigen::Vector3d f = sim->total_contact_force();
    line += fmt::format(",{:.9g},{:.9g},{:.9g}", f.x(), f.y(), f.z());
    for (LinkIndex link : contact_links) line += fmt::format(",{:.9g}", sim->total_contact_force(link).z());
    csv << line << "\n";
  };

  // Servos persist: a later command changes only what it names.
  std::vector<ScenarioServo> servo(n);
  auto apply = [&](const ScenarioCommand& command) {
    for (const auto& [link, v] : command.tracks) sim->set_track_speed(link, v);
    for (const auto& [link, s] : command.joints) {
      ScenarioServo& current = servo[link];
      if (s.target) current.target = s.target;
      if (s.p) current.p = s.p;
      if (s.d) current.d = s.d;
      if (s.torque) current.torque = s.torque;
      JointServo js;
      js.p_gain = current.p.value_or(0);
      js.d_gain = current.d.value_or(0);
      const double target = current.target.value_or(0);
      js.q_ref = [target](double) { return target; };
      js.torque = current.torque.value_or(0);
      sim->set_servo(link, js);
    }
  };
  const long long rows = std::llround(scenario.duration / scenario.sample);
  std::size_t next = 0;
  try {
    while (next < scenario.commands.size() && scenario.commands[next].time <= 0) apply(scenario.commands[next++]);
    row();
    for (long long k = 1; k <= rows; ++k) {
      const double t = std::min(scenario.duration, static_cast<double>(k) * scenario.sample);
      // Commands take effect at their own time, between samples too.
      while (next < scenario.commands.size() && scenario.commands[next].time <= t) {
        // Commands at one time are applied together: the integrator restarts once for them.
        if (scenario.commands[next].time > sim->time()) sim->advance_to(scenario.commands[next].time);
        apply(scenario.commands[next++]);
      }
      sim->advance_to(t);
      if (!sim->finite()) {
        report_rule(sink, "internal-error", model.source,
                    fmt::format("the simulation diverged (a non-finite state) at t = {:g} s", sim->time()));
        return false;
      }
      row();
    }
    if (stats) *stats = {sim->steps_taken(), sim->force_evaluations()};
  } catch (const WorkBudgetExceeded& e) {
    // The caller reports it at its cause; when that is the commands, at the last one applied.
    if (e.by_commands && next > 0) throw WorkBudgetExceeded(e.what(), scenario.commands[next - 1].at, true);
    throw;
  } catch (const std::exception& e) {
    report_rule(sink, "internal-error", model.source, std::string("Simbody failed: ") + e.what());
    return false;
  }
  return true;
}

}  // namespace bodyfmt::dynamics
