#include "fix_run.h"

#include <bodyfmt/derived.h>
#include <bodyfmt/diagnostic_policy.h>
#include <bodyfmt/fix.h>
#include <bodyfmt/geometry_fix.h>
#include <bodyfmt/geometry_mass.h>
#include <bodyfmt/load.h>
#include <bodyfmt/read_file.h>
#include <bodyfmt/rules.h>
#include <bodyfmt/validate.h>

#include <fmt/format.h>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <set>
#include <sstream>

namespace fs = std::filesystem;

namespace bodyfmt::tools {
namespace {

std::string canonical(const std::string& path) {
  std::error_code ec;
  const fs::path p = fs::weakly_canonical(path, ec);
  return ec ? path : p.string();
}

// Bounded like every file a tool reads (bodyfmt/read_file.h); the loader read it within the
// same limit moments ago.
std::optional<std::string> read_text(const std::string& path, std::string& why) {
  return read_regular_file(path, LoadOptions{}.max_file_bytes, why);
}

/// One file to rewrite: where, and its new text.
struct Rewrite {
  std::string path;  ///< canonical (a symbolic link is followed, so the link stays)
  std::string shown;
  std::string before;
  std::string after;
};

/// Writes every rewrite or none: each new text goes to a temporary file beside its target
/// (same permissions), and only when all are written and synced are they renamed over their
/// targets. A read-only target or folder is refused before anything is written.
bool write_all(const std::vector<Rewrite>& rewrites, std::string& why) {
  for (const Rewrite& r : rewrites) {
    // A file without any write permission is read-only by intent, even for root (whom
    // access() would let through).
    struct stat st {};
    if (::stat(r.path.c_str(), &st) == 0 && (st.st_mode & 0222) == 0) {
      why = fmt::format("{}: the file is read-only (mode {:04o})", r.shown, st.st_mode & 07777);
      return false;
    }
    if (::access(r.path.c_str(), W_OK) != 0) {
      why = r.shown + ": the file is not writable (" + std::strerror(errno) + ")";
      return false;
    }
  }
  std::vector<std::string> temporaries;
  const auto abandon = [&] {
    for (const std::string& t : temporaries) ::unlink(t.c_str());
    return false;
  };
  for (const Rewrite& r : rewrites) {
    struct stat st {};
    if (::stat(r.path.c_str(), &st) != 0) {
      why = r.shown + ": " + std::strerror(errno);
      return abandon();
    }
    const fs::path target(r.path);
    std::string pattern = (target.parent_path() / ("." + target.filename().string() + ".bodycheck-XXXXXX")).string();
    const int fd = ::mkstemp(pattern.data());
    if (fd < 0) {
      why = r.shown + ": cannot create a temporary file in its folder (" + std::strerror(errno) + ")";
      return abandon();
    }
    temporaries.push_back(pattern);
    std::size_t written = 0;
    bool ok = true;
    while (ok && written < r.after.size()) {
      const ssize_t n = ::write(fd, r.after.data() + written, r.after.size() - written);
      if (n < 0 && errno == EINTR) continue;
      ok = n > 0;
      if (ok) written += static_cast<std::size_t>(n);
    }
    ok = ok && ::fchmod(fd, st.st_mode & 07777) == 0 && ::fsync(fd) == 0;
    const int saved = errno;
    ok = ::close(fd) == 0 && ok;
    if (!ok) {
      why = r.shown + ": cannot write the temporary file (" + std::strerror(saved) + ")";
      return abandon();
    }
  }
  for (std::size_t i = 0; i < rewrites.size(); ++i) {
    if (::rename(temporaries[i].c_str(), rewrites[i].path.c_str()) != 0) {
      why = rewrites[i].shown + ": cannot replace the file (" + std::strerror(errno) + ")";
      for (std::size_t j = i; j < temporaries.size(); ++j) ::unlink(temporaries[j].c_str());
      return false;
    }
  }
  return true;
}

class ModelFixer {
 public:
  ModelFixer(Front& front, const std::set<std::string>& named, const FixSettings& settings, FixSummary& summary)
      : front_(front), named_(named), settings_(settings), summary_(summary) {}

  void fix(const std::string& file) {
    if (file == "-") return fail(file, "standard input cannot be fixed in place; name the file");
    auto policy = front_.policy_for(file);
    if (!policy) return fail(file, "its .bodycheck.yaml is malformed");
    if (settings_.geometry) return fix_geometry(file, *policy);
    LoadOptions options = front_.load_options();
    options.load_meshes = false;  // fix-its never touch meshes; the model is compared without them
    CollectingSink collected;
    DiagnosticPolicy filter(collected, policy->options);
    const std::optional<Model> original = load_body(file, options, filter);
    original_ = original ? &*original : nullptr;
    bool fatal = !original;
    for (const Diagnostic& d : collected.diagnostics()) fatal = fatal || d.severity == Severity::kFatal;
    if (fatal) {
      front_.print(collected.diagnostics());
      return fail(file, "the file does not load (see the errors above); nothing is written");
    }

    if (settings_.upgrade) {
      const std::string refused = degree_values_refusal(collected.diagnostics());
      if (!refused.empty()) return fail(file, refused);
    }

    // Units of edits that stand or fall together: each safe fix-it alone, the upgrade whole
    // (its angles only mean the same model with its new header).
    std::vector<Unit> units;
    for (const Diagnostic& d : collected.diagnostics()) {
      if (d.rule_id == "load-format-upgrade" && settings_.upgrade && allowed(d.location.file)) {
        if (d.fixes.empty()) return fail(file, "cannot upgrade: " + d.message);
        for (const FixIt& f : d.fixes)
          if (!allowed(f.file))
            return fail(file, "the upgrade also rewrites angles in \"" + f.file.str() +
                                  "\"; name that file on the command line too, or use --fix-includes");
      }
      Unit upgrade{{}, d.location, true};
      for (const FixIt& f : d.fixes) {
        const bool wanted = f.safety == FixSafety::kSafe || (f.safety == FixSafety::kUpgrade && settings_.upgrade);
        if (!wanted || !allowed(f.file)) continue;
        if (f.safety == FixSafety::kUpgrade)
          upgrade.fixes.push_back(f);
        else
          units.push_back(Unit{{f}, SourceLocation{f.file, f.line, f.column}, false});
      }
      if (!upgrade.fixes.empty()) units.push_back(std::move(upgrade));
    }
    apply_units(file, units);
  }

 private:
  /// Why the format upgrade is refused, or "": a value of a file to upgrade that a finding still
  /// calls degrees would be converted as radians (-10 to -572.958), and the finding, which judges
  /// radian files only, would be gone. The user decides first: reinterpret it, or suppress the
  /// finding if it is radians after all.
  std::string degree_values_refusal(const std::vector<Diagnostic>& findings) const {
    std::vector<const FixIt*> conversions;
    for (const Diagnostic& d : findings)
      if (d.rule_id == "load-format-upgrade" && allowed(d.location.file))
        for (const FixIt& f : d.fixes) conversions.push_back(&f);
    if (conversions.empty()) return "";
    std::vector<const Diagnostic*> standing;
    for (const Diagnostic& d : findings)
      if ((d.rule_id == "units-range-looks-degree" || d.rule_id == "units-velocity-looks-degree") &&
          allowed(d.location.file))
        standing.push_back(&d);
    if (standing.empty()) return "";
    const Diagnostic& d = *standing.front();
    // The upgrade's edits of the value: on its line, from its column on (a flow pair or a scalar).
    std::vector<std::string> converted;
    for (const FixIt* f : conversions)
      if (f->file == d.location.file && f->line == d.location.line && f->column >= d.location.column)
        converted.push_back(f->original + " -> " + f->replacement);
    return fmt::format(
        "cannot upgrade while {} value{} look{} like degrees: {}:{}:{}: {} [{}]. The upgrade converts {} as "
        "radians{}{}, and the finding would be gone. If they are degrees, apply the finding's fix-it (reinterpret as "
        "degrees; a quick fix in the editor) or write them in radians; if they are radians, suppress the finding "
        "(# bodycheck: disable={}); then upgrade",
        standing.size(), standing.size() == 1 ? "" : "s", standing.size() == 1 ? "s" : "", d.location.file.str(),
        d.location.line, d.location.column, d.message, d.rule_id, standing.size() == 1 ? "it" : "them",
        converted.empty() ? "" : " (", converted.empty() ? "" : fmt::format("{})", fmt::join(converted, ", ")),
        d.rule_id);
  }

  /// Edits that stand or fall together, and where to point when they are left out.
  struct Unit {
    std::vector<FixIt> fixes;
    SourceLocation where;
    bool upgrade = false;
  };

  /// `--fix=geometry`: the links an inertia rule flags (with `--all-links`: every link) get
  /// their mass data recomputed from their shapes, each part at its written mass: the link-level
  /// centre of mass and inertia from the shapes below no RigidBody element, each RigidBody
  /// element's from the shapes below it. The proof is the same re-load, compared with the
  /// original model whose recomputed parts hold the written numbers.
  void fix_geometry(const std::string& file, const Front::FilePolicy& policy) {
    CollectingSink collected;
    DiagnosticPolicy filter(collected, policy.options);
    const std::optional<Model> original = load_body(file, front_.load_options(), filter);
    bool fatal = !original;
    for (const Diagnostic& d : collected.diagnostics()) fatal = fatal || d.severity == Severity::kFatal;
    if (fatal) {
      front_.print(collected.diagnostics());
      return fail(file, "the file does not load (see the errors above); nothing is written");
    }
    std::vector<bool> chosen(original->links.size(), true);
    if (!settings_.all_links) {
      const Derived derived = compute_derived(*original, filter);
      CollectingSink checked;
      DiagnosticPolicy check_filter(checked, policy.options);
      validate::check_model(*original, derived, {}, check_filter);
      chosen = links_for_geometry_fix(*original, checked.diagnostics());
    }

    Model expected = *original;
    std::vector<Unit> units;
    std::vector<Diagnostic> notes;
    CollectingSink shapes;
    for (std::size_t i = 0; i < original->links.size(); ++i) {
      if (!chosen[i]) continue;
      const Link& link = original->links[i];
      // A link without mass data (a massless frame) has nothing to recompute.
      if (settings_.all_links && link.mass_contributions.empty()) continue;
      const LinkGeometryMass geometry = link_geometry_mass(*original, link, shapes);
      const std::optional<GeometryAtWrittenMass> at = geometry_at_written_mass(link, geometry);
      const SourceLocation where = first_known({link.sources.inertia(), link.sources.mass(), link.source});
      const auto unavailable = [&](const SourceLocation& at_place, const std::string& why) {
        notes.push_back(make_diagnostic("fix-geometry-unavailable", at_place,
                                        "no centre of mass and inertia from the geometry: " + why));
      };
      if (!at) {
        unavailable(where, geometry.no_solid()
                               ? fmt::format("link \"{}\" has no solid {} geometry", link.name,
                                             geometry.from_visual ? "visual" : "collision")
                               : fmt::format("link \"{}\" has no link-level mass key, and no RigidBody element "
                                             "with a mass around its shapes",
                                             link.name));
        continue;
      }
      // Each part is a unit of its own: one written behind an alias leaves the others fixable.
      if (at->link_keys) {
        std::string why;
        std::vector<FixIt> fixes;
        const std::string mass_file = link.sources.mass().file.str();
        if (const std::optional<std::string> text = read_text(mass_file, why))
          fixes = link_mass_fixes(*text, mass_file, link, *at->link_keys, why);
        if (!fixes.empty() && !allowed(mass_file)) {
          why = "its keys are written in \"" + mass_file +
                "\"; name that file on the command line too, or use --fix-includes";
          fixes.clear();
        }
        if (fixes.empty()) {
          unavailable(where, why);
        } else {
          const MassProperties written = written_mass_keys(*at->link_keys);
          for (MassContribution& c : expected.links[i].mass_contributions) {
            if (!c.from_link_keys) continue;
            c.center_of_mass = written.center_of_mass;
            c.inertia = written.inertia;
          }
          units.push_back(Unit{std::move(fixes), where, false});
        }
      }
      for (const RecomputedRigidBody& body : at->rigid_bodies) {
        const MassContribution& c = link.mass_contributions[body.contribution];
        std::string why;
        std::vector<FixIt> fixes;
        const std::string body_file = c.source.file.str();
        if (const std::optional<std::string> text = read_text(body_file, why))
          fixes = rigid_body_mass_fixes(*text, body_file, link, body.contribution, body.as_written, why);
        if (!fixes.empty() && !allowed(body_file)) {
          why = "the RigidBody element is written in \"" + body_file +
                "\"; name that file on the command line too, or use --fix-includes";
          fixes.clear();
        }
        if (fixes.empty()) {
          unavailable(c.source, why);
          continue;
        }
        // What the loader will make of the written numbers: read through the element's frame.
        const MassProperties written = written_mass_keys(body.as_written);
        const Eigen::Affine3d X_LF = rigid_body_frame(link, body.contribution);
        const Eigen::Matrix3d L = X_LF.linear();
        MassContribution& e = expected.links[i].mass_contributions[body.contribution];
        e.center_of_mass = X_LF * written.center_of_mass;
        e.inertia = L * written.inertia * L.transpose();
        units.push_back(Unit{std::move(fixes), c.source, false});
      }
    }
    std::vector<Diagnostic> shown = shapes.diagnostics();
    shown.insert(shown.end(), notes.begin(), notes.end());
    if (!shown.empty()) front_.print(shown);
    original_ = &expected;
    reload_meshes_ = true;
    apply_units(file, units);
  }

  static Eigen::Affine3d rigid_body_frame(const Link& link, std::size_t contribution) {
    for (std::size_t f = 0; f < link.frames.size(); ++f)
      if (link.frames[f].rigid_body == static_cast<int>(contribution)) return frame_in_link(link, static_cast<int>(f));
    return Eigen::Affine3d::Identity();
  }

  void apply_units(const std::string& file, const std::vector<Unit>& units) {
    if (units.empty()) return;

    Attempt attempt = try_units(file, units);
    if (attempt.failure.empty() && !attempt.difference.empty()) {
      // An edit of text that another use shares (an anchor merged into two joints, a value
      // aliased elsewhere) changes that use too. Each unit alone finds which: those that change
      // the model by themselves are left out, with a note, and the rest is fixed.
      if (units.size() > kMostUnitsTried)
        return fail(file, "the fixed text would load a different model (" + attempt.difference +
                              "); nothing is written (a bug in a fix-it: please report it)");
      std::vector<Unit> kept;
      std::vector<std::pair<const Unit*, std::string>> left_out;
      for (const Unit& unit : units) {
        const Attempt alone = try_units(file, {unit});
        if (!alone.failure.empty()) return fail(file, alone.failure);
        if (alone.difference.empty())
          kept.push_back(unit);
        else
          left_out.emplace_back(&unit, alone.difference);
      }
      attempt = kept.empty() ? Attempt{} : try_units(file, kept);
      if (!attempt.failure.empty()) return fail(file, attempt.failure);
      if (!attempt.difference.empty())
        return fail(file, "the fixed text would load a different model (" + attempt.difference +
                              "); nothing is written (a bug in a fix-it: please report it)");
      for (const auto& [unit, difference] : left_out) {
        const Diagnostic note = make_diagnostic(
            "fix-left-out", unit->where,
            fmt::format("{} left as it is: the edited text is shared with another use (an anchor, alias or merge), "
                        "which the edit would change too ({})",
                        unit->upgrade ? "the format upgrade is" : "this fix-it is", difference),
            unit->upgrade ? "give each use its own copy of the shared text, then run --fix --upgrade again"
                          : "give each use its own copy of the shared text, then run --fix again");
        front_.print(std::vector<Diagnostic>{note});
      }
    } else if (!attempt.failure.empty()) {
      return fail(file, attempt.failure);
    }
    if (attempt.rewrites.empty()) return;

    if (settings_.dry_run) {
      for (const Rewrite& r : attempt.rewrites) summary_.diff += unified_diff(r.before, r.after, r.shown);
    } else {
      std::string why;
      if (!write_all(attempt.rewrites, why)) return fail(file, why + "; nothing is written");
      for (const Rewrite& r : attempt.rewrites)
        std::cerr << fmt::format("{}: fixed ({} edit{})\n", r.shown, edits_in(attempt.by_file[r.path]),
                                 edits_in(attempt.by_file[r.path]) == 1 ? "" : "s");
    }
    summary_.files_changed += static_cast<int>(attempt.rewrites.size());
    summary_.edits += attempt.edits;
  }

  /// The outcome of applying some units: the files to rewrite, or why not. `failure` stops the
  /// fix of this model; `difference` says how the fixed text loads another model.
  struct Attempt {
    std::vector<Rewrite> rewrites;
    std::map<std::string, std::vector<FixIt>> by_file;  // canonical path -> edits
    int edits = 0;
    std::string failure;
    std::string difference;
  };
  /// Beyond this many units, a model that changes is reported whole rather than searched.
  static constexpr std::size_t kMostUnitsTried = 256;

  Attempt try_units(const std::string& file, const std::vector<Unit>& units) {
    Attempt a;
    std::map<std::string, std::string> shown;  // canonical path -> name to show
    for (const Unit& unit : units)
      for (const FixIt& f : unit.fixes) {
        const std::string key = canonical(f.file);
        a.by_file[key].push_back(f);
        shown.emplace(key, f.file.str());
      }
    LoadOptions reload_options = front_.load_options();
    reload_options.load_meshes = reload_meshes_;
    const std::string main_key = canonical(file);
    std::string main_text;
    for (auto& [key, fixes] : a.by_file) {
      std::string why;
      const std::optional<std::string> before = read_text(key, why);
      if (!before) {
        a.failure = shown[key] + ": cannot read it: " + why;
        return a;
      }
      std::optional<std::string> after = apply_fixes(*before, fixes, why);
      if (!after) {
        a.failure = why;
        return a;
      }
      a.edits += count_edits(fixes);
      if (key == main_key)
        main_text = *after;
      else
        reload_options.file_texts[key] = *after;
      if (*after != *before) a.rewrites.push_back(Rewrite{key, shown[key], *before, std::move(*after)});
    }
    if (a.rewrites.empty()) return a;
    if (!a.by_file.count(main_key)) {
      std::string why;
      auto text = read_text(file, why);
      if (!text) {
        a.failure = "cannot read it: " + why;
        return a;
      }
      main_text = std::move(*text);
    }
    // The proof: the fixed text loads to the same model.
    CollectingSink reload_sink;
    const std::optional<Model> fixed = load_body_string(main_text, file, reload_options, reload_sink);
    bool reload_fatal = !fixed;
    for (const Diagnostic& d : reload_sink.diagnostics()) reload_fatal = reload_fatal || d.severity == Severity::kFatal;
    if (reload_fatal) {
      a.difference = "the fixed text does not load";
      return a;
    }
    if (auto difference = model_difference(*original_, *fixed)) a.difference = *difference;
    return a;
  }

  bool allowed(const std::string& path) const { return settings_.includes || named_.count(canonical(path)) != 0; }

  static int count_edits(std::vector<FixIt> fixes) {
    std::sort(fixes.begin(), fixes.end(),
              [](const FixIt& a, const FixIt& b) { return std::tie(a.begin, a.end) < std::tie(b.begin, b.end); });
    fixes.erase(std::unique(fixes.begin(), fixes.end()), fixes.end());
    return static_cast<int>(fixes.size());
  }
  static int edits_in(const std::vector<FixIt>& fixes) { return count_edits(fixes); }

  void fail(const std::string& file, const std::string& why) {
    front_.print_error(file + ": cannot fix: " + why);
    summary_.failed = true;
  }

  Front& front_;
  const Model* original_ = nullptr;  ///< the model being fixed, as loaded (--fix=geometry: as it should load)
  bool reload_meshes_ = false;       ///< --fix=geometry compares a model loaded with its meshes
  const std::set<std::string>& named_;
  const FixSettings& settings_;
  FixSummary& summary_;
};

}  // namespace

FixSummary run_fixes(Front& front, const std::vector<std::string>& files, const FixSettings& settings) {
  FixSummary summary;
  std::set<std::string> named;
  for (const std::string& file : files) named.insert(canonical(file));
  ModelFixer fixer(front, named, settings, summary);
  for (const std::string& file : files) fixer.fix(file);
  return summary;
}

}  // namespace bodyfmt::tools
