#include "load/appearance.h"

#include <bodyfmt/body_keys.h>

#include "load/mapping_reader.h"
#include "load/scalar.h"
#include "load/uri.h"
#include "load/values.h"

#include <fmt/format.h>

#include <algorithm>
#include <filesystem>
#include <system_error>

namespace bodyfmt::detail {
Appearance read_appearance(LoadContext& ctx, const yaml::NodeRef& appearance) {
  Appearance result;
  if (!appearance->is_mapping()) {
    // Choreonoid reads appearance as an optional mapping: anything else is ignored (SR1DH
    // has an empty `appearance:` whose material slipped to the Shape's indentation level).
    ctx.report("load-ignored-value", appearance,
               appearance->is_null() ? "this appearance is empty; Choreonoid ignores it"
                                     : "appearance must be a mapping; Choreonoid ignores this value",
               "indent material and texture under appearance");
    return result;
  }
  MappingReader r(ctx, appearance, "appearance");
  if (yaml::NodeRef m = r.take({"material"})) {
    if (mapping_or_ignored(ctx, m, "material")) {
      Material material;
      MappingReader mr(ctx, m, "material");
      assign_if(material.ambient_intensity, take_optional_double(mr, {"ambient", "ambientIntensity"}));
      // Colours and transparency are fractions: Choreonoid keeps any number and the renderer
      // clamps it, so the model keeps it too and the exporters write the clamped value.
      auto fraction = [&](const yaml::NodeRef& at, const char* key, double value) {
        if (value >= 0.0 && value <= 1.0) return;
        ctx.report("appearance-value-range", at,
                   fmt::format("{} {:g} is outside 0..1; renderers and exporters use {:g}", key, value,
                               std::clamp(value, 0.0, 1.0)),
                   "write a value from 0 to 1");
      };
      auto colour = [&](const yaml::NodeRef& v, const char* key, Eigen::Vector3d& into) {
        const std::optional<Eigen::Vector3d> c = read_optional_vec3(ctx, v);
        if (!c) return;
        into = *c;
        for (int i = 0; i < 3; ++i) {
          if ((*c)[i] < 0.0 || (*c)[i] > 1.0) {
            fraction(v, key, (*c)[i]);
            break;
          }
        }
      };
      if (auto v = mr.take({"diffuse", "diffuseColor"})) colour(v, "diffuse", material.diffuse_color);
      if (auto v = mr.take({"emissive", "emissiveColor"})) {
        colour(v, "emissive", material.emissive_color);
        // An exporter that cannot write the colour names this key (its spelling's entry).
        const yaml::MapEntry* entry = m->find("emissive");
        material.emissive_source = (entry ? entry : m->find("emissiveColor"))->key_location;
      }
      if (auto v = mr.take({"specular", "specularColor"})) colour(v, "specular", material.specular_color);
      // Choreonoid falls back to shininess whenever specular_exponent does not read as a number.
      yaml::NodeRef exponent_node = mr.take({"specular_exponent"});
      const std::optional<double> exponent = exponent_node ? optional_double(ctx, exponent_node) : std::nullopt;
      if (exponent) {
        material.specular_exponent = *exponent;
        if (auto shininess = mr.take({"shininess"}))
          ctx.report("load-ignored-key", shininess,
                     "\"shininess\" is ignored by Choreonoid when specular_exponent is given", "remove shininess");
      } else if (auto shininess = mr.take({"shininess"})) {
        // body-format-spec §8.7: legacy VRML shininess maps to an exponent.
        if (auto s = optional_double(ctx, shininess)) {
          material.specular_exponent = 127.0 * std::clamp(*s, 0.0, 1.0) + 1.0;
          ctx.report("load-legacy-shininess", shininess,
                     "legacy key \"shininess\"; the modern key is \"specular_exponent\"",
                     "write specular_exponent: " + std::to_string(material.specular_exponent));
        }
      }
      if (auto v = mr.take({"transparency"})) {
        if (auto t = optional_double(ctx, v)) {
          material.transparency = *t;
          fraction(v, "transparency", *t);
        }
      }
      mr.report_unknown(body_key_names("material"));
      result.material = material;
    }
  }
  // StdSceneReader::readTexture reads `repeat` (with toBool, which throws) and then
  // readAppearance the texture_transform only once the image has loaded. The image file
  // being there is as near as bodyfmt gets to that (it does not decode images).
  bool image_read = false;
  if (yaml::NodeRef t = r.take({"texture"})) {
    if (t->is_mapping()) {
      Texture texture;
      MappingReader tr(ctx, t, "texture");
      if (auto uri = tr.take({"uri", "url"})) {
        texture.uri = uri->scalar();
        texture.resolved_path = resolve_uri(ctx, uri, texture.uri, uri->location.file);
        std::error_code ec;
        image_read = !texture.uri.empty() && !texture.resolved_path.empty() &&
                     std::filesystem::is_regular_file(texture.resolved_path, ec);
      }
      auto read_bool = [&](const yaml::NodeRef& v) {
        return image_read ? required_bool(ctx, v) : optional_bool(ctx, v);
      };
      if (auto repeat = tr.take({"repeat"})) {
        if (repeat->is_sequence() && repeat->items().size() == 2) {
          assign_if(texture.repeat_s, read_bool(repeat.child(repeat->items()[0])));
          assign_if(texture.repeat_t, read_bool(repeat.child(repeat->items()[1])));
        } else if (repeat->is_sequence() && image_read) {
          ctx.report("load-vector-size", repeat, "the number of the repeat elements must be two");
        } else if (repeat->is_sequence()) {
          ctx.report("load-ignored-value", repeat,
                     "the number of the repeat elements must be two; Choreonoid reads repeat only once the texture "
                     "image has loaded, and this one is not found");
        } else {
          auto b = read_bool(repeat);
          assign_if(texture.repeat_s, b);
          assign_if(texture.repeat_t, b);
        }
      } else {
        assign_if(texture.repeat_s, take_optional_bool(tr, {"repeat_s", "repeatS"}));
        assign_if(texture.repeat_t, take_optional_bool(tr, {"repeat_t", "repeatT"}));
      }
      tr.report_unknown(body_key_names("texture"));
      result.texture = texture;
    } else {
      mapping_or_ignored(ctx, t, "texture");  // findMapping: warns and skips
    }
  }
  if (yaml::NodeRef transform = r.take({"texture_transform", "textureTransform"});
      transform && transform->is_mapping()) {
    if (const yaml::MapEntry* rotation = transform->find("rotation"))
      ctx.note_angle(transform.child(rotation->value));  // a scalar angle (§8.7)
    // readTextureTransform: Vector2 reads (findListing, then a fatal size check).
    for (std::string_view key : {"center", "scale", "translation"}) {
      const yaml::MapEntry* e = image_read ? transform->find(key) : nullptr;
      if (!e) continue;
      const yaml::NodeRef value = transform.child(e->value);
      if (listing_or_ignored(ctx, value, key)) read_vector(ctx, value, 2);
    }
  }
  r.report_unknown(body_key_names("appearance"));
  return result;
}

}  // namespace bodyfmt::detail
