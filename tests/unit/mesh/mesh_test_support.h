#pragma once
// Helpers for the mesh import tests: bounding boxes of assets and reference `visual_bbox`
// values read from /work/shared/corpus/reference/**.ref.yaml.

#include <bodyfmt/model.h>

#include <fstream>
#include <optional>
#include <sstream>
#include <string>

namespace mesh_test {

inline const std::string kCorpus = std::string(BODYFMT_SHARED_DIR) + "/corpus/choreonoid/";
inline const std::string kReference = std::string(BODYFMT_SHARED_DIR) + "/corpus/reference/";

inline bodyfmt::BoundingBox box_of(const bodyfmt::MeshAsset& asset,
                                   const Eigen::Affine3d& t = Eigen::Affine3d::Identity()) {
  bodyfmt::BoundingBox box;
  for (const auto& part : asset.parts) {
    for (const auto& v : part.mesh.vertices) box.add(t * v);
  }
  return box;
}

inline std::size_t triangle_count(const bodyfmt::MeshAsset& asset) {
  std::size_t n = 0;
  for (const auto& part : asset.parts) n += part.mesh.triangles.size();
  return n;
}

/// `visual_bbox` of link `link` in a reference file (min xyz, max xyz), if present.
inline std::optional<bodyfmt::BoundingBox> reference_visual_bbox(const std::string& ref_file, const std::string& link) {
  std::ifstream in(kReference + ref_file);
  std::string line;
  bool in_link = false;
  while (std::getline(in, line)) {
    if (line.rfind("- name: ", 0) == 0) in_link = line == "- name: \"" + link + "\"";
    const auto pos = line.find("visual_bbox: [");
    if (in_link && pos != std::string::npos) {
      std::string values = line.substr(pos + 14);
      for (char& c : values)
        if (c == ',' || c == ']') c = ' ';
      std::istringstream s(values);
      bodyfmt::BoundingBox box;
      s >> box.min.x() >> box.min.y() >> box.min.z() >> box.max.x() >> box.max.y() >> box.max.z();
      if (!s) return std::nullopt;
      return box;
    }
  }
  return std::nullopt;
}

/// Per axis: within 1e-3 m or 1 % of the reference size.
inline bool boxes_match(const bodyfmt::BoundingBox& a, const bodyfmt::BoundingBox& ref) {
  if (a.empty()) return false;
  for (int i = 0; i < 3; ++i) {
    const double tol = std::max(1e-3, 0.01 * (ref.max[i] - ref.min[i]));
    if (std::abs(a.min[i] - ref.min[i]) > tol || std::abs(a.max[i] - ref.max[i]) > tol) return false;
  }
  return true;
}

inline std::string to_string(const bodyfmt::BoundingBox& b) {
  std::ostringstream s;
  s << "[" << b.min.transpose() << " | " << b.max.transpose() << "]";
  return s.str();
}

}  // namespace mesh_test
