// SPDX-License-Identifier: MIT
// libFuzzer target: the STL reader on arbitrary bytes (written to a file, as
// the reader reads files), then the mesh's topology and one sphere's
// contacts with it. Any outcome but a mesh or a tumble::Error is a bug. Run
// by scripts/fuzz.sh.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <numeric>
#include <string>
#include <vector>

#include "io/stl.hpp"
#include "tumble/core/error.hpp"
#include "tumble/walls/mesh.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    static const std::filesystem::path file =
        std::filesystem::temp_directory_path() / ("tumble-fuzz-" + std::to_string(::getpid()) + ".stl");
    std::ofstream(file, std::ios::binary | std::ios::trunc).write(reinterpret_cast<const char*>(data),
                                                                 static_cast<std::streamsize>(size));
    try {
        const tumble::MeshTopology mesh(tumble::io::read_stl(file));
        std::vector<std::uint32_t> faces(mesh.face_count());
        std::iota(faces.begin(), faces.end(), 0u);
        std::vector<tumble::MeshContact> out;
        tumble::mesh_contacts(mesh, mesh.vertices()[0] + tumble::Vec3{0.1, 0.2, 0.3}, 0.5, faces, out);
    } catch (const tumble::Error&) {
    }
    return 0;
}
