#include "sculpt/core/files/mesh_file.h"

#include <cctype>
#include <string>

#include "sculpt/core/files/glb_file.h"
#include "sculpt/core/mesh/mesh_reader.h"

namespace sculpt::core {
namespace {

std::string lower_extension(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  for (char& c : ext)
    c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

}  // namespace

bool is_mesh_file_name(const std::filesystem::path& path) {
  const std::string ext = lower_extension(path);
  return ext == ".obj" || ext == ".ply" || ext == ".stl" || ext == ".glb";
}

Result<Mesh> read_mesh_file(const std::filesystem::path& path) {
  if (!is_mesh_file_name(path))
    return Error(path.string() + ": unknown mesh extension '" + path.extension().string() +
                 "' (.glb, .obj, .ply, .stl)");
  if (lower_extension(path) == ".glb") return read_glb(path);
  return read_mesh(path);
}

double mesh_unit_mm(const std::filesystem::path& path) {
  return lower_extension(path) == ".glb" ? 1000.0 : 1.0;
}

}  // namespace sculpt::core
