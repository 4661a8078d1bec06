// Tests of the I/O library: round trips through every format, each reader on hand-written samples, and
// hostile input (lying headers, truncation, garbage), which must fail with a message and never crash.
#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cstdlib>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <limits>
#include <optional>
#include <random>
#include <string>
#include <thread>
#include <vector>

#if defined(__unix__) || defined(__APPLE__)
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>
#endif

#include "io/formats.h"
#include "io/mesh_io.h"
#include "io/ply_stream_writer.h"
#include "io/text_scan.h"

using namespace dbrg::io;

namespace {

const MeshFormat ALL_FORMATS[] = {MeshFormat::ply_binary, MeshFormat::ply_ascii, MeshFormat::obj,
                                  MeshFormat::off,        MeshFormat::xyz,       MeshFormat::stl};

bool same_bits(const std::vector<double>& a, const std::vector<double>& b) {
    return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0);
}

bool same_properties(const std::vector<VertexProperty>& a, const std::vector<VertexProperty>& b) {
    if (a.size() != b.size()) return false;
    for (size_t i = 0; i < a.size(); ++i) {
        if (a[i].name != b[i].name || a[i].type != b[i].type || a[i].bytes != b[i].bytes) return false;
    }
    return true;
}

bool same_mesh(const MeshData& a, const MeshData& b) {
    return same_bits(a.positions, b.positions) && a.triangles == b.triangles && a.normals == b.normals &&
           same_properties(a.properties, b.properties) && a.has_faces == b.has_faces && a.non_finite_at == b.non_finite_at;
}

// Reads `bytes` through a source that hands them out 1 to 7 at a time into a 16-byte first buffer, as
// a file (`size_known`) or a pipe is read, so that every line, token and value straddles refills.
IoStatus read_in_pieces(std::string_view bytes, MeshFormat format, bool size_known, MeshData& out) {
    size_t at = 0, turn = 0;
    ByteSource source(
        [&](char* destination, size_t capacity) {
            const size_t piece = std::min({capacity, bytes.size() - at, 1 + turn++ % 7});
            std::copy_n(bytes.data() + at, piece, destination);
            at += piece;
            return piece;
        },
        size_known ? std::optional<uint64_t>(bytes.size()) : std::nullopt, 16);
    return read_mesh_source(source, format, out);
}

// Reads `bytes` at once with read_mesh_buffer, and checks that reading them in pieces gives the same:
// the same mesh and message when their size is known, the same mesh or a failure when it is not (then
// a lying count shows only when the data runs out, and STL cannot tell ascii by the size).
IoStatus read_text(std::string_view bytes, MeshFormat format, MeshData& out) {
    const IoStatus status = read_mesh_buffer(bytes.data(), bytes.size(), format, out);
    MeshData piecewise;
    const IoStatus piecewise_status = read_in_pieces(bytes, format, true, piecewise);
    CHECK(piecewise_status.ok == status.ok);
    CHECK(piecewise_status.message == status.message);
    CHECK(same_mesh(piecewise, out));
    if (format != MeshFormat::stl) {
        const IoStatus unsized_status = read_in_pieces(bytes, format, false, piecewise);
        CHECK(unsized_status.ok == status.ok);
        CHECK(same_mesh(piecewise, out));
    }
    return status;
}

// Reads text that must be accepted; fails the test with the reader's message otherwise.
MeshData read_ok(std::string_view text, MeshFormat format) {
    MeshData mesh;
    const IoStatus status = read_text(text, format, mesh);
    INFO(status.message);
    CHECK(status.ok);
    return mesh;
}

// Reads text that must be rejected with a message containing `expected`.
void check_rejected(std::string_view text, MeshFormat format, const std::string& expected) {
    MeshData mesh;
    const IoStatus status = read_text(text, format, mesh);
    INFO("message: ", status.message);
    INFO("expected: ", expected);
    CHECK_FALSE(status.ok);
    CHECK(status.message.find(expected) != std::string::npos);
    CHECK(mesh.positions.empty());
    CHECK(mesh.triangles.empty());
}

std::vector<uint32_t> tris(std::initializer_list<uint32_t> indices) { return indices; }

// Values in either byte order, for hand-built binary PLY and STL files.
struct ByteWriter {
    bool big_endian = false;
    std::string bytes;

    ByteWriter& text(std::string_view s) {
        bytes.append(s);
        return *this;
    }
    template <class T>
    ByteWriter& put(T value) {
        unsigned char raw[sizeof(T)];
        std::memcpy(raw, &value, sizeof(T));
        for (size_t i = 0; i < sizeof(T); ++i) bytes.push_back(static_cast<char>(raw[big_endian ? sizeof(T) - 1 - i : i]));
        return *this;
    }
};

// A mesh whose coordinates need all 17 significant digits, plus tiny, huge and subnormal values.
MeshData awkward_mesh() {
    MeshData mesh;
    mesh.positions = {0.1, 1.0 / 3.0, -2.0 / 7.0, 1e-300, 1e300, 5e-324, 3.141592653589793, -0.0, 123456789.123456789,
                      -1.0, 2.0, 0.30000000000000004};
    mesh.triangles = {0, 1, 2, 0, 2, 3, 3, 2, 1};
    mesh.has_faces = true;
    return mesh;
}

// A mesh whose coordinates are exact in float32, for STL.
MeshData float_exact_mesh() {
    MeshData mesh;
    mesh.positions = {0, 0, 0, 1.5, 0, 0, 0, 2.25, 0, 0, 0, -3.125};
    mesh.triangles = {0, 2, 1, 0, 1, 3, 1, 2, 3, 2, 0, 3};
    mesh.has_faces = true;
    return mesh;
}

// The corner positions of each triangle, which survive a renumbering of the vertices.
std::vector<std::array<double, 9>> triangle_corners(const MeshData& mesh) {
    std::vector<std::array<double, 9>> corners;
    for (size_t t = 0; t < mesh.triangle_count(); ++t) {
        std::array<double, 9> c;
        for (size_t k = 0; k < 3; ++k) {
            for (size_t a = 0; a < 3; ++a) c[3 * k + a] = mesh.positions[3 * mesh.triangles[3 * t + k] + a];
        }
        corners.push_back(c);
    }
    return corners;
}

std::string temp_path(const std::string& name) {
    const char* dir = std::getenv("TMPDIR");
    return std::string(dir ? dir : "/tmp") + "/dbrg_test_io_" + std::to_string(std::random_device()()) + "_" + name;
}

// Writes `bytes` to a new temporary file named like `name`; returns its path.
std::string write_temp_file(const std::string& name, std::string_view bytes) {
    const std::string path = temp_path(name);
    std::FILE* file = std::fopen(path.c_str(), "wb");
    REQUIRE(file);
    const size_t written = std::fwrite(bytes.data(), 1, bytes.size(), file);
    std::fclose(file);
    REQUIRE(written == bytes.size());
    return path;
}

double seconds_since(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

#if defined(__SANITIZE_ADDRESS__)
const bool SANITIZED = true;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
const bool SANITIZED = true;
#else
const bool SANITIZED = false;
#endif
#else
const bool SANITIZED = false;
#endif


#if defined(__unix__) || defined(__APPLE__)
const bool HAVE_FIFOS = true;

// What read_mesh made of a FIFO named like `name` that a thread fed with `start` and then `filler`
// bytes without end (stopping only at 256 MiB, so that a reader which takes everything ends the test
// and fails it), and how many bytes the thread got into the pipe.
struct FifoRead {
    IoStatus status;
    MeshData mesh;
    uint64_t bytes_written = 0;
};

FifoRead read_endless_fifo(const std::string& name, const std::string& start, char filler) {
    const std::string path = temp_path(name);
    REQUIRE(mkfifo(path.c_str(), 0600) == 0);
    // A write into a pipe whose reader has gone must fail with EPIPE rather than kill the test.
    const auto previous_handler = std::signal(SIGPIPE, SIG_IGN);
    std::atomic<uint64_t> written{0};
    std::thread writer([&] {
        // Opening without blocking (it fails until the reader has opened) cannot hang the test.
        int fd = -1;
        const auto begun = std::chrono::steady_clock::now();
        while ((fd = open(path.c_str(), O_WRONLY | O_NONBLOCK)) < 0 && seconds_since(begun) < 10) std::this_thread::yield();
        if (fd < 0) return;
        fcntl(fd, F_SETFL, fcntl(fd, F_GETFL) & ~O_NONBLOCK);
        const std::string fill(64 << 10, filler);
        std::string_view pending = start;
        while (written < (uint64_t(256) << 20)) {
            if (pending.empty()) pending = fill;
            const ssize_t count = write(fd, pending.data(), pending.size());
            if (count <= 0) break;
            written += static_cast<uint64_t>(count);
            pending.remove_prefix(static_cast<size_t>(count));
        }
        close(fd);
    });
    FifoRead result;
    result.status = read_mesh(path, result.mesh);
    writer.join();
    std::signal(SIGPIPE, previous_handler);
    std::remove(path.c_str());
    result.bytes_written = written;
    return result;
}
#else
const bool HAVE_FIFOS = false;
#endif

} // namespace

TEST_CASE("format_from_path knows the extensions in any letter case") {
    CHECK(format_from_path("a/b/mesh.ply") == MeshFormat::ply_binary);
    CHECK(format_from_path("MESH.PLY") == MeshFormat::ply_binary);
    CHECK(format_from_path("x.obj") == MeshFormat::obj);
    CHECK(format_from_path("x.Off") == MeshFormat::off);
    CHECK(format_from_path("x.xyz") == MeshFormat::xyz);
    CHECK(format_from_path("x.pts") == MeshFormat::xyz);
    CHECK(format_from_path("x.stl") == MeshFormat::stl);
    CHECK_FALSE(format_from_path("x.txt"));
    CHECK_FALSE(format_from_path("noextension"));
    CHECK_FALSE(format_from_path("dir.ply/noextension"));
    CHECK_FALSE(format_from_path(""));
    CHECK(std::string(format_name(MeshFormat::ply_ascii)) == "ply_ascii");
}

TEST_CASE("every format round-trips positions exactly") {
    const MeshData mesh = awkward_mesh();
    for (MeshFormat format : {MeshFormat::ply_binary, MeshFormat::ply_ascii, MeshFormat::obj, MeshFormat::off, MeshFormat::xyz}) {
        CAPTURE(format_name(format));
        std::string bytes;
        REQUIRE(write_mesh_buffer(mesh, format, bytes).ok);
        MeshData back;
        const IoStatus status = read_text(bytes, format, back);
        INFO(status.message);
        REQUIRE(status.ok);
        CHECK(same_bits(back.positions, mesh.positions));
        if (format == MeshFormat::xyz) {
            CHECK(back.triangles.empty());
            CHECK_FALSE(back.has_faces);
        } else {
            CHECK(back.triangles == mesh.triangles);
            CHECK(back.has_faces);
        }
    }
}

TEST_CASE("STL round-trips float32 coordinates and the triangles' corners") {
    const MeshData mesh = float_exact_mesh();
    std::string bytes;
    REQUIRE(write_mesh_buffer(mesh, MeshFormat::stl, bytes).ok);
    CHECK(bytes.size() == 84 + 50 * mesh.triangle_count());
    CHECK(bytes.compare(0, 5, "solid") != 0);
    const MeshData back = read_ok(bytes, MeshFormat::stl);
    CHECK(back.vertex_count() == 4);  // corners shared by several triangles are merged again
    CHECK(triangle_corners(back) == triangle_corners(mesh));
}

TEST_CASE("binary PLY uses float32 when that is lossless, float64 otherwise") {
    std::string bytes;
    REQUIRE(write_mesh_buffer(float_exact_mesh(), MeshFormat::ply_binary, bytes).ok);
    CHECK(bytes.find("property float x") != std::string::npos);
    REQUIRE(write_mesh_buffer(awkward_mesh(), MeshFormat::ply_binary, bytes).ok);
    CHECK(bytes.find("property double x") != std::string::npos);
    const MeshData back = read_ok(bytes, MeshFormat::ply_binary);
    CHECK(same_bits(back.positions, awkward_mesh().positions));
}

TEST_CASE("non-finite coordinates round-trip as they are") {
    MeshData mesh;
    const double inf = std::numeric_limits<double>::infinity();
    mesh.positions = {std::nan(""), inf, -inf};
    for (MeshFormat format : {MeshFormat::ply_binary, MeshFormat::ply_ascii, MeshFormat::obj, MeshFormat::off, MeshFormat::xyz}) {
        CAPTURE(format_name(format));
        std::string bytes;
        REQUIRE(write_mesh_buffer(mesh, format, bytes).ok);
        const MeshData back = read_ok(bytes, format);
        REQUIRE(back.positions.size() == 3);
        CHECK(std::isnan(back.positions[0]));
        CHECK(back.positions[1] == inf);
        CHECK(back.positions[2] == -inf);
    }
}

namespace {

// Text built a line at a time, counting the lines.
struct LineWriter {
    std::string text;
    size_t lines = 0;

    // Appends `line` and returns its place as the readers name it ("line 7").
    std::string add(const std::string& line) {
        text += line + "\n";
        return line_place(++lines);
    }
};

std::string number_text(double value) {
    std::string text;
    append_values(text, &value, 1);
    return text;
}

// A file in one format whose third and fourth vertices each hold the given value among their coordinates,
// and the places of those two values as a reader must name them. Values that are not coordinates (normals,
// colours, extra columns) are non-finite everywhere: the readers must not judge them.
struct PlacedSample {
    std::string file_name;  // its extension chooses the reader
    MeshFormat format;
    std::string bytes;
    std::string third_place, fourth_place;
};

std::vector<PlacedSample> placed_samples(double third, double fourth) {
    const std::string t = number_text(third), f = number_text(fourth);
    std::vector<PlacedSample> samples;
    {
        PlacedSample s{"points.xyz", MeshFormat::xyz, "", "", ""};
        LineWriter w;
        w.add("# x y z intensity");
        w.add("0 0 0 nan");
        w.add("");
        w.add("1,0,0,inf");
        s.third_place = w.add("0 " + t + " 1 nan");
        s.fourth_place = w.add(f + " 1 1 -inf");
        s.bytes = w.text;
        samples.push_back(s);
    }
    {
        PlacedSample s{"mesh.obj", MeshFormat::obj, "", "", ""};
        LineWriter w;
        w.add("# a comment");
        w.add("vn nan 0 0");
        w.add("v 0 0 0 nan nan nan");
        w.add("v 1 0 0");
        w.add("vt inf 0");
        s.third_place = w.add("v 0 1 " + t);
        s.fourth_place = w.add("v " + f + " 0 1");
        w.add("f 1 2 3 4");
        s.bytes = w.text;
        samples.push_back(s);
    }
    {
        PlacedSample s{"mesh.off", MeshFormat::off, "", "", ""};
        LineWriter w;
        w.add("COFF");
        w.add("# vertices, faces, edges");
        w.add("4 1 0");
        w.add("0 0 0 nan 0 0 1");
        w.add("1 0 0 inf 0 0 1");
        s.third_place = w.add(t + " 1 0 0 nan 0 1");
        w.add("");
        s.fourth_place = w.add("0 0 " + f + " 0 0 nan 1");
        w.add("4 0 1 2 3");
        s.bytes = w.text;
        samples.push_back(s);
    }
    {
        PlacedSample s{"ascii.ply", MeshFormat::ply_ascii, "", "", ""};
        LineWriter w;
        for (const char* line : {"ply", "format ascii 1.0", "element vertex 4", "property float nx", "property float x",
                                 "property float y", "property float z", "element face 1",
                                 "property list uchar int vertex_indices", "end_header"}) {
            w.add(line);
        }
        w.add("nan 0 0 0");
        w.add("inf 1 0 0");
        // Values may be laid out on any lines: the place is the line of the value itself.
        w.add("nan 0");
        s.third_place = w.add(t + " 1");
        s.fourth_place = w.add("-inf 0 0 " + f);
        w.add("4 0 1 2 3");
        s.bytes = w.text;
        samples.push_back(s);
    }
    {
        PlacedSample s{"binary.ply", MeshFormat::ply_binary, "", "", ""};
        ByteWriter w;
        w.big_endian = true;
        w.text("ply\nformat binary_big_endian 1.0\nelement vertex 4\nproperty float nx\nproperty double x\n"
               "property float y\nproperty double z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n");
        const double nan = std::nan("");
        w.put(float(nan)).put(0.0).put(0.0f).put(0.0);
        w.put(float(nan)).put(1.0).put(0.0f).put(0.0);
        w.put(float(nan)).put(0.0).put(1.0f);
        s.third_place = byte_place(w.bytes.size());
        w.put(third);
        w.put(float(nan));
        s.fourth_place = byte_place(w.bytes.size());
        w.put(fourth).put(0.0f).put(1.0);
        w.put(uint8_t(4)).put(int32_t(0)).put(int32_t(1)).put(int32_t(2)).put(int32_t(3));
        s.bytes = w.bytes;
        samples.push_back(s);
    }
    {
        PlacedSample s{"binary.stl", MeshFormat::stl, "", "", ""};
        ByteWriter w;
        w.text(std::string(80, ' ')).put(uint32_t(2));
        const float nan = std::nanf("");
        // Corners repeat across triangles; the third and fourth distinct ones hold the values.
        w.put(nan).put(nan).put(nan).put(0.0f).put(0.0f).put(0.0f).put(1.0f).put(0.0f).put(0.0f).put(0.0f).put(1.0f);
        s.third_place = byte_place(w.bytes.size());
        w.put(float(third)).put(uint16_t(0));
        w.put(nan).put(nan).put(nan).put(0.0f).put(0.0f).put(0.0f).put(1.0f).put(0.0f).put(0.0f);
        s.fourth_place = byte_place(w.bytes.size());
        w.put(float(fourth)).put(0.0f).put(1.0f).put(uint16_t(0));
        s.bytes = w.bytes;
        samples.push_back(s);
    }
    {
        PlacedSample s{"ascii.stl", MeshFormat::stl, "", "", ""};
        LineWriter w;
        w.add("solid placed");
        w.add("facet normal nan nan nan");
        w.add("outer loop");
        w.add("vertex 0 0 0");
        w.add("vertex 1 0 0");
        s.third_place = w.add("vertex 0 " + t + " 0");
        w.add("endloop");
        w.add("endfacet");
        w.add("facet normal inf 0 0");
        w.add("outer loop");
        w.add("vertex 0 0 0");
        w.add("vertex 1 0 0");
        s.fourth_place = w.add("vertex 0 0 " + f);
        w.add("endloop");
        w.add("endfacet");
        w.add("endsolid placed");
        s.bytes = w.text;
        samples.push_back(s);
    }
    return samples;
}

// The index of the first vertex with a non-finite coordinate (the one the library names), or -1.
int64_t first_non_finite_vertex(const MeshData& mesh) {
    for (size_t i = 0; i < mesh.positions.size(); ++i) {
        if (!std::isfinite(mesh.positions[i])) return static_cast<int64_t>(i / 3);
    }
    return -1;
}

} // namespace

TEST_CASE("readers name the place of the first non-finite vertex coordinate, and only of that") {
    const double nan = std::nan(""), inf = std::numeric_limits<double>::infinity();
    const struct {
        double third, fourth;
        int64_t first_bad_vertex;  // -1: none
    } cases[] = {{nan, 1.0, 2}, {inf, -inf, 2}, {-inf, nan, 2}, {0.5, nan, 3}, {0.5, 1.0, -1}};
    for (const auto& c : cases) {
        const std::vector<PlacedSample> samples = placed_samples(c.third, c.fourth);
        for (const PlacedSample& sample : samples) {
            CAPTURE(sample.file_name);
            CAPTURE(c.third);
            CAPTURE(c.fourth);
            const MeshData mesh = read_ok(sample.bytes, sample.format);
            REQUIRE(mesh.vertex_count() == 4);
            CHECK(first_non_finite_vertex(mesh) == c.first_bad_vertex);
            const std::string expected = c.first_bad_vertex == 2 ? sample.third_place : c.first_bad_vertex == 3 ? sample.fourth_place : "";
            CHECK(mesh.non_finite_at == expected);

            // A file gives what its bytes in memory give.
            const std::string path = write_temp_file(sample.file_name, sample.bytes);
            MeshData from_file;
            const IoStatus status = read_mesh(path, from_file);
            std::remove(path.c_str());
            INFO(status.message);
            CHECK(status.ok);
            CHECK(same_mesh(from_file, mesh));
        }
    }
}


TEST_CASE("files round-trip through write_mesh and read_mesh") {
    const MeshData mesh = float_exact_mesh();
    for (const std::string extension : {".ply", ".obj", ".off", ".stl", ".xyz", ".pts"}) {
        CAPTURE(extension);
        const std::string path = temp_path("round" + extension);
        REQUIRE(write_mesh(path, mesh).ok);
        MeshData back;
        const IoStatus status = read_mesh(path, back);
        INFO(status.message);
        REQUIRE(status.ok);
        // STL numbers vertices in the order the triangles first use them.
        if (extension != ".stl") CHECK(same_bits(back.positions, mesh.positions));
        if (back.has_faces) CHECK(triangle_corners(back) == triangle_corners(mesh));
        std::remove(path.c_str());
    }
    const std::string ascii = temp_path("ascii.ply");
    REQUIRE(write_mesh(ascii, mesh, MeshFormat::ply_ascii).ok);
    MeshData back;
    REQUIRE(read_mesh(ascii, back).ok);
    CHECK(back.triangles == mesh.triangles);
    std::remove(ascii.c_str());
}

TEST_CASE("file errors name the path") {
    MeshData mesh;
    IoStatus status = read_mesh("/nonexistent/dir/mesh.ply", mesh);
    CHECK_FALSE(status.ok);
    CHECK(status.message.find("/nonexistent/dir/mesh.ply") != std::string::npos);
    status = read_mesh("mesh.unknown", mesh);
    CHECK_FALSE(status.ok);
    CHECK(status.message.find("unknown file type") != std::string::npos);
    status = write_mesh("/nonexistent/dir/out.obj", float_exact_mesh());
    CHECK_FALSE(status.ok);
    CHECK(status.message.find("/nonexistent/dir/out.obj") != std::string::npos);
    status = read_mesh("/", mesh);
    CHECK_FALSE(status.ok);
    // A directory with a mesh's name: said plainly (it once surfaced as a string-reserve exception).
    const std::string directory = (std::filesystem::temp_directory_path() / "dbrg_test_directory.ply").string();
    std::filesystem::create_directory(directory);
    status = read_mesh(directory, mesh);
    CHECK_FALSE(status.ok);
    CHECK(status.message == directory + ": a directory, not a file");
    std::filesystem::remove(directory);
}

TEST_CASE("writers refuse malformed meshes") {
    MeshData mesh = float_exact_mesh();
    mesh.triangles.push_back(7);
    mesh.triangles.push_back(0);
    mesh.triangles.push_back(1);
    std::string bytes;
    const IoStatus status = write_mesh_buffer(mesh, MeshFormat::obj, bytes);
    CHECK_FALSE(status.ok);
    CHECK(status.message.find("refers to vertex 7") != std::string::npos);
    mesh.positions.push_back(1.0);
    CHECK_FALSE(write_mesh_buffer(mesh, MeshFormat::off, bytes).ok);
}

TEST_CASE("ascii PLY with extra properties, elements, comments and polygons") {
    const char* text =
        "ply\r\n"
        "format ascii 1.0\r\n"
        "comment made by hand\r\n"
        "obj_info anything\r\n"
        "element vertex 5\r\n"
        "property uchar red\r\n"
        "property float x\r\n"
        "property float y\r\n"
        "property list uchar float extra\r\n"
        "property double z\r\n"
        "element face 2\r\n"
        "property int flags\r\n"
        "property list uchar int vertex_index\r\n"
        "element edge 1\r\n"
        "property int vertex1\r\n"
        "property int vertex2\r\n"
        "end_header\r\n"
        "255 0 0 2 7 8 0\r\n"
        "1 1 0 0 0.5\r\n"
        "2 1 1 1 9 -1.5e2\r\n"
        "3 0 1 0 +4\r\n"
        "4 2 2 0 5\r\n"
        "7 3 0 1 2\r\n"
        "7 4 0 2 3 4\r\n"
        "0 1\r\n";
    const MeshData mesh = read_ok(text, MeshFormat::ply_ascii);
    CHECK(mesh.positions == std::vector<double>{0, 0, 0, 1, 0, 0.5, 1, 1, -150, 0, 1, 4, 2, 2, 5});
    CHECK(mesh.triangles == tris({0, 1, 2, 0, 2, 3, 0, 3, 4}));
    CHECK(mesh.has_faces);
}

TEST_CASE("ascii PLY values may be laid out on any lines") {
    const MeshData mesh = read_ok("ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                                  "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0 1 0\n0 0 1 0 3 0 1\n2\n",
                                  MeshFormat::ply_ascii);
    CHECK(mesh.vertex_count() == 3);
    CHECK(mesh.triangles == tris({0, 1, 2}));
}

TEST_CASE("big-endian binary PLY with mixed property types") {
    ByteWriter w;
    w.big_endian = true;
    w.text("ply\nformat binary_big_endian 1.0\nelement vertex 4\nproperty char tag\nproperty double x\nproperty short s\n"
           "property double y\nproperty double z\nproperty list ushort uchar junk\n"
           "element face 1\nproperty list ushort uint16 vertex_indices\nend_header\n");
    const double coords[4][3] = {{0.1, 0.2, 0.3}, {-1.5, 2.5, 1e-10}, {7, 8, 9}, {1e100, -1e-100, 0}};
    for (int v = 0; v < 4; ++v) {
        w.put<int8_t>(-5).put<double>(coords[v][0]).put<int16_t>(-300).put<double>(coords[v][1]).put<double>(coords[v][2]);
        w.put<uint16_t>(static_cast<uint16_t>(v));  // a junk list of v bytes
        for (int j = 0; j < v; ++j) w.put<uint8_t>(0xEE);
    }
    w.put<uint16_t>(4).put<uint16_t>(3).put<uint16_t>(2).put<uint16_t>(1).put<uint16_t>(0);
    const MeshData mesh = read_ok(w.bytes, MeshFormat::ply_binary);
    REQUIRE(mesh.vertex_count() == 4);
    for (int v = 0; v < 4; ++v) {
        for (int k = 0; k < 3; ++k) CHECK(mesh.positions[3 * v + k] == coords[v][k]);
    }
    CHECK(mesh.triangles == tris({3, 2, 1, 3, 1, 0}));
}

TEST_CASE("little-endian binary PLY with float coordinates, int counts and trailing bytes") {
    ByteWriter w;
    w.text("ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float32 x\nproperty float32 y\nproperty float32 z\n"
           "property uint8 confidence\nelement face 1\nproperty list int32 int32 vertex_indices\nend_header\n");
    for (int v = 0; v < 3; ++v) w.put<float>(0.25f * static_cast<float>(v)).put<float>(-1.0f).put<float>(3.0f).put<uint8_t>(9);
    w.put<int32_t>(3).put<int32_t>(0).put<int32_t>(1).put<int32_t>(2);
    w.text("trailing bytes are ignored");
    const MeshData mesh = read_ok(w.bytes, MeshFormat::ply_ascii);  // either PLY format reads any PLY
    CHECK(mesh.positions == std::vector<double>{0, -1, 3, 0.25, -1, 3, 0.5, -1, 3});
    CHECK(mesh.triangles == tris({0, 1, 2}));
}

TEST_CASE("PLY triangle strips alternate orientation, restart at -1, and drop joining triangles") {
    const char* header = "ply\nformat ascii 1.0\nelement vertex 8\nproperty float x\nproperty float y\nproperty float z\n"
                         "element tristrips 1\nproperty list int int vertex_indices\nend_header\n";
    std::string text = header;
    for (int v = 0; v < 8; ++v) text += std::to_string(v) + " " + std::to_string(v % 2) + " 0\n";
    // 0 1 2 3 | restart | 4 5 6 6 7: the (5, 6, 6) and (6, 6, 7) triangles only join the pieces.
    text += "11 0 1 2 3 -1 4 5 6 6 7 7\n";
    const MeshData mesh = read_ok(text, MeshFormat::ply_ascii);
    CHECK(mesh.triangles == tris({0, 1, 2, 2, 1, 3, 4, 5, 6}));
    CHECK(mesh.has_faces);

    std::string joined = header;
    for (int v = 0; v < 8; ++v) joined += "0 0 " + std::to_string(v) + "\n";
    // A single strip made of two pieces joined by repeating 3 and 4: 0 1 2 3 3 4 4 5 6.
    joined += "9 0 1 2 3 3 4 4 5 6\n";
    const MeshData strip = read_ok(joined, MeshFormat::ply_ascii);
    // The second piece's first triangle sits at an even position of the strip, so it keeps its order.
    CHECK(strip.triangles == tris({0, 1, 2, 2, 1, 3, 4, 5, 6}));
}

TEST_CASE("OBJ: v/vt/vn forms, negative indices, polygons, and everything else ignored") {
    const char* text =
        "# a comment\n"
        "mtllib scene.mtl\n"
        "o thing\n"
        "v 0 0 0\n"
        "v 1 0 0 1.0\n"
        "v 1 1 0 0.5 0.5 0.5\n"
        "v 0 1 0\n"
        "vt 0 0\nvn 0 0 1\nvp 0.5\n"
        "g group\nusemtl red\ns off\n"
        "f 1 2 3\n"
        "f 1/1 3/1 4/1 # trailing comment\n"
        "f 1//1 2//1 3//1\n"
        "f -4/1/1 -3/1/1 -2/1/1 -1/1/1\n"
        "l 1 2\n"
        "p 1\n"
        "\n"
        "v +2 -3 4e1\n"
        "f -1 1 2\n";
    const MeshData mesh = read_ok(text, MeshFormat::obj);
    CHECK(mesh.positions == std::vector<double>{0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 2, -3, 40});
    CHECK(mesh.triangles == tris({0, 1, 2, 0, 2, 3, 0, 1, 2, 0, 1, 2, 0, 2, 3, 4, 0, 1}));
    CHECK(mesh.has_faces);
}

TEST_CASE("OBJ faces may name vertices defined further down") {
    const MeshData mesh = read_ok("f 1 2 3\nv 0 0 0\nv 1 0 0\nv 0 1 0\n", MeshFormat::obj);
    CHECK(mesh.triangles == tris({0, 1, 2}));
}

TEST_CASE("OFF: comments, counts beside the keyword, colour columns, polygons") {
    const char* text =
        "# leading comment\n"
        "COFF 4 2 0 # counts on the keyword line\n"
        "\n"
        "0 0 0 255 0 0 255\n"
        "1 0 0 0 255 0 255\n"
        "# between vertices\n"
        "1 1 0 0 0 255 255\n"
        "0 1 0 1 1 1 1\n"
        "3 0 1 2 0.5 0.5 0.5\n"
        "4 0 1 2 3\n";
    const MeshData mesh = read_ok(text, MeshFormat::off);
    CHECK(mesh.positions == std::vector<double>{0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0});
    CHECK(mesh.triangles == tris({0, 1, 2, 0, 1, 2, 0, 2, 3}));

    const MeshData plain = read_ok("OFF\n3 1\n0 0 0\n1 0 0\n0 1 0\n3 2 1 0\n", MeshFormat::off);
    CHECK(plain.triangles == tris({2, 1, 0}));
    CHECK(read_ok("OFF\n0 0 0\n", MeshFormat::off).vertex_count() == 0);
}

TEST_CASE("XYZ and PTS: blanks or commas, extra columns, comments, a leading count") {
    const MeshData xyz = read_ok("# x y z\n1 2 3\n4,5,6\n 7 , 8 ,9 , 100 200\n\n1e3\t2e3\t3e3 0.5\n// done\n", MeshFormat::xyz);
    CHECK(xyz.positions == std::vector<double>{1, 2, 3, 4, 5, 6, 7, 8, 9, 1000, 2000, 3000});
    CHECK_FALSE(xyz.has_faces);
    const MeshData pts = read_ok("2\n1 2 3 10 255 255 255\n4 5 6 11 0 0 0\n", MeshFormat::xyz);
    CHECK(pts.positions == std::vector<double>{1, 2, 3, 4, 5, 6});
}

TEST_CASE("ascii STL, and a binary STL whose header begins with 'solid'") {
    const char* text =
        "solid cube_corner\n"
        "  facet normal 0 0 -1\n"
        "    outer loop\n"
        "      vertex 0 0 0\n"
        "      vertex 0 1 0\n"
        "      vertex 1 0 0\n"
        "    endloop\n"
        "  endfacet\n"
        "  facet normal 0 -1 0\n"
        "    outer loop\n"
        "      vertex 0 0 0\n"
        "      vertex 1 0 0\n"
        "      vertex 0 0 1\n"
        "    endloop\n"
        "  endfacet\n"
        "endsolid cube_corner\n";
    const MeshData mesh = read_ok(text, MeshFormat::stl);
    CHECK(mesh.positions == std::vector<double>{0, 0, 0, 0, 1, 0, 1, 0, 0, 0, 0, 1});
    CHECK(mesh.triangles == tris({0, 1, 2, 0, 2, 3}));

    std::string binary;
    REQUIRE(write_mesh_buffer(float_exact_mesh(), MeshFormat::stl, binary).ok);
    binary.replace(0, 5, "solid");
    CHECK(read_ok(binary, MeshFormat::stl).triangle_count() == 4);
}

TEST_CASE("empty input") {
    for (MeshFormat format : ALL_FORMATS) {
        CAPTURE(format_name(format));
        MeshData mesh;
        const IoStatus status = read_mesh_buffer(nullptr, 0, format, mesh);
        // Empty OBJ and XYZ files are valid and hold nothing; the other formats need a header.
        if (format == MeshFormat::obj || format == MeshFormat::xyz) {
            CHECK(status.ok);
        } else {
            CHECK_FALSE(status.ok);
            CHECK_FALSE(status.message.empty());
        }
        CHECK(mesh.vertex_count() == 0);
    }
    MeshData mesh;
    CHECK_FALSE(read_mesh_buffer(nullptr, 10, MeshFormat::obj, mesh).ok);
}

TEST_CASE("hostile PLY headers") {
    const std::string xyz = "property float x\nproperty float y\nproperty float z\n";
    check_rejected("plyx\n", MeshFormat::ply_binary, "does not begin with the line 'ply'");
    check_rejected("ply\n", MeshFormat::ply_binary, "without 'end_header'");
    check_rejected("ply\nend_header\n", MeshFormat::ply_binary, "no 'format' line");
    check_rejected("ply\nformat ascii 2.0\nend_header\n", MeshFormat::ply_binary, "unsupported PLY version");
    check_rejected("ply\nformat binary_middle_endian 1.0\nend_header\n", MeshFormat::ply_binary, "unknown format");
    check_rejected("ply\nformat ascii 1.0\nformat ascii 1.0\nend_header\n", MeshFormat::ply_binary, "second 'format'");
    check_rejected("ply\nelement vertex 1\n", MeshFormat::ply_binary, "expected 'format'");
    check_rejected("ply\nformat ascii 1.0\nproperty float x\nend_header\n", MeshFormat::ply_binary, "before any 'element'");
    check_rejected("ply\nformat ascii 1.0\nelement vertex -3\n" + xyz + "end_header\n", MeshFormat::ply_binary, "non-negative integer");
    check_rejected("ply\nformat ascii 1.0\nelement vertex 99999999999999999999999\n", MeshFormat::ply_binary, "non-negative integer");
    check_rejected("ply\nformat ascii 1.0\nelement vertex 4294967295\n" + xyz + "end_header\n", MeshFormat::ply_binary, "at most 4294967294");
    check_rejected("ply\nformat ascii 1.0\nelement vertex 1\nproperty quad x\n", MeshFormat::ply_binary, "unknown type 'quad'");
    check_rejected("ply\nformat ascii 1.0\nelement vertex 1\nproperty list uchar\n", MeshFormat::ply_binary, "count type and an item type");
    check_rejected("ply\nformat ascii 1.0\nelement vertex 1\nproperty float\n", MeshFormat::ply_binary, "without a name");
    check_rejected("ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float x\n", MeshFormat::ply_binary, "two properties named 'x'");
    check_rejected("ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nend_header\n", MeshFormat::ply_binary, "lacks an x, y or z");
    check_rejected("ply\nformat ascii 1.0\nelement vertex 1\nproperty list uchar float x\n", MeshFormat::ply_binary, "is a list");
    check_rejected("ply\nformat ascii 1.0\nelement vertex 1\n" + xyz + "element vertex 1\n", MeshFormat::ply_binary, "second 'vertex'");
    check_rejected("ply\nformat ascii 1.0\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n3 0 0 0\n", MeshFormat::ply_binary,
                   "no 'vertex' element");
    check_rejected("ply\nformat ascii 1.0\nelement vertex 1\n" + xyz + "element face 1\nproperty list float int vertex_indices\n", MeshFormat::ply_binary,
                   "count type of property 'vertex_indices' is not an integer type");
    check_rejected("ply\nformat ascii 1.0\nelement vertex 1\n" + xyz + "element face 1\nproperty list uchar float vertex_indices\n", MeshFormat::ply_binary,
                   "are not integers");
    check_rejected("ply\nformat ascii 1.0\nelement vertex 1\n" + xyz + "element face 1\nproperty int vertex_indices\n", MeshFormat::ply_binary,
                   "is not a list");
    check_rejected("ply\nformat ascii 1.0\nelement vertex 1\n" + xyz + "element face 1\nproperty int flags\nend_header\n", MeshFormat::ply_binary,
                   "has no vertex_indices list");
    check_rejected("ply\nformat ascii 1.0\nbogus line\n", MeshFormat::ply_binary, "header line 3: unknown header keyword 'bogus'");
}

TEST_CASE("PLY headers: a size limit, and repeated property names found among thousands") {
    const std::string head = "ply\nformat ascii 1.0\nelement vertex 0\nproperty float x\nproperty float y\nproperty float z\nelement junk 0\n";
    std::string many = head;
    for (int i = 0; i < 100000; ++i) many += "property float p" + std::to_string(i) + "\n";
    check_rejected(many + "end_header\n", MeshFormat::ply_ascii, "the header is longer than 1048576 bytes");
    std::string distinct = head;
    for (int i = 0; i < 30000; ++i) distinct += "property float p" + std::to_string(i) + "\n";
    REQUIRE(distinct.size() < (1 << 20));
    CHECK(read_ok(distinct + "end_header\n", MeshFormat::ply_ascii).vertex_count() == 0);
    check_rejected(distinct + "property float p12345\nend_header\n", MeshFormat::ply_ascii,
                   "header line 30008: element 'junk' has two properties named 'p12345'");
    // Names are compared within their element only.
    CHECK(read_ok(head + "property float x\nend_header\n", MeshFormat::ply_ascii).vertex_count() == 0);
}

TEST_CASE("a lying PLY header fails fast without allocating for its counts") {
    const std::string xyz = "property float x\nproperty float y\nproperty float z\n";
    const auto start = std::chrono::steady_clock::now();
    check_rejected("ply\nformat binary_little_endian 1.0\nelement vertex 4000000000\n" + xyz + "end_header\n0123456789abcdef",
                   MeshFormat::ply_binary, "declares 4000000000 items, more than the rest of the file can hold");
    check_rejected("ply\nformat ascii 1.0\nelement vertex 4000000000\n" + xyz + "end_header\n1 2 3\n", MeshFormat::ply_ascii,
                   "more than the rest of the file can hold");
    check_rejected("ply\nformat binary_little_endian 1.0\nelement vertex 0\n" + xyz +
                       "element face 4000000000\nproperty list uchar int vertex_indices\nend_header\n\x03",
                   MeshFormat::ply_binary, "element 'face' declares 4000000000 items");
    check_rejected("ply\nformat binary_big_endian 1.0\nelement vertex 4294967294\nproperty double x\nproperty double y\nproperty double z\n"
                   "end_header\n",
                   MeshFormat::ply_binary, "more than the rest of the file can hold");
    // An element without properties takes no bytes, however many items it claims: read past at once.
    const MeshData mesh = read_ok("ply\nformat binary_little_endian 1.0\nelement nothing 9223372036854775807\nelement vertex 0\n" + xyz + "end_header\n",
                                  MeshFormat::ply_binary);
    CHECK(mesh.vertex_count() == 0);
    CHECK(seconds_since(start) < 1.0);
}

TEST_CASE("hostile PLY bodies") {
    const std::string ascii_head = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n";
    const std::string face_list = "element face 1\nproperty list uchar int vertex_indices\nend_header\n";
    const std::string vertices = "0 0 0\n1 0 0\n0 1 0\n";
    check_rejected(ascii_head + face_list + vertices + "3 0 1 3\n", MeshFormat::ply_ascii, "PLY line 13: face 0: vertex index 3 is out of range (the file has 3 vertices)");
    check_rejected(ascii_head + face_list + vertices + "3 0 1 -1\n", MeshFormat::ply_ascii, "vertex index -1 is out of range");
    check_rejected(ascii_head + face_list + vertices + "2 0 1\n", MeshFormat::ply_ascii, "a face with 2 corners");
    check_rejected(ascii_head + face_list + vertices + "-3 0 1 2\n", MeshFormat::ply_ascii, "negative list length -3");
    check_rejected(ascii_head + face_list + vertices + "1000000 0 1 2\n", MeshFormat::ply_ascii, "list length 1000000 is more than the rest");
    check_rejected(ascii_head + face_list + vertices + "3 0 1\n", MeshFormat::ply_ascii, "ends in the middle of the data");
    check_rejected(ascii_head + face_list + vertices + "3 0 1 2.5\n", MeshFormat::ply_ascii, "expected an integer, found '2.5'");
    check_rejected(ascii_head + face_list + "0 0 0\n1 zero 0\n0 1 0\n", MeshFormat::ply_ascii, "PLY line 11: expected a number, found 'zero'");
    check_rejected(ascii_head + face_list + "0 0 0\n1 1e999 0\n0 1 0\n", MeshFormat::ply_ascii, "expected a number, found '1e999'");
    check_rejected(ascii_head + "element tristrips 1\nproperty list int int vertex_indices\nend_header\n" + vertices + "4 0 1 -2 2\n",
                   MeshFormat::ply_ascii, "tristrips 0: vertex index -2 is out of range");

    // A megabyte-long token is reported, shortened.
    MeshData mesh;
    const std::string huge = ascii_head + face_list + std::string(1 << 20, 'q') + " 0 0\n";
    const IoStatus status = read_text(huge, MeshFormat::ply_ascii, mesh);
    CHECK_FALSE(status.ok);
    CHECK(status.message.size() < 200);

    const std::string binary_head = "ply\nformat binary_little_endian 1.0\nelement vertex 2\nproperty float x\nproperty float y\nproperty float z\n";
    ByteWriter w;
    w.text(binary_head + "element face 1\nproperty list uint int vertex_indices\nend_header\n");
    for (int i = 0; i < 6; ++i) w.put<float>(1.0f);
    const std::string good_vertices = w.bytes;
    w.put<uint32_t>(0xFFFFFFFFu).put<int32_t>(0);
    check_rejected(w.bytes, MeshFormat::ply_binary, "list length 4294967295 is more than the rest of the file can hold");
    w.bytes = good_vertices;
    w.put<uint32_t>(3).put<int32_t>(0).put<int32_t>(1).put<int32_t>(-7);
    check_rejected(w.bytes, MeshFormat::ply_binary, "vertex index -7 is out of range");
    w.bytes = good_vertices;
    w.put<uint32_t>(3).put<int32_t>(0).put<int32_t>(1);
    check_rejected(w.bytes, MeshFormat::ply_binary, "more than the rest of the file can hold");
    check_rejected(good_vertices.substr(0, good_vertices.size() - 3), MeshFormat::ply_binary, "declares 2 items");

    ByteWriter negative;
    negative.text(binary_head + "element face 1\nproperty list char uint vertex_indices\nend_header\n");
    for (int i = 0; i < 6; ++i) negative.put<float>(0.0f);
    negative.put<int8_t>(-1);
    check_rejected(negative.bytes, MeshFormat::ply_binary, "negative list length -1");

    // Truncation that the element sizes cannot foresee (lists) is reported with its byte offset.
    ByteWriter cut;
    cut.text(binary_head + "element face 2\nproperty list uchar int vertex_indices\nend_header\n");
    for (int i = 0; i < 6; ++i) cut.put<float>(0.0f);
    cut.put<uint8_t>(3).put<int32_t>(0).put<int32_t>(1).put<int32_t>(1);
    cut.put<uint8_t>(3);
    check_rejected(cut.bytes, MeshFormat::ply_binary, "list length 3 is more than the rest of the file can hold");
    cut.bytes.pop_back();
    cut.put<uint8_t>(1).put<int32_t>(0);
    check_rejected(cut.bytes, MeshFormat::ply_binary, "face 1: a face with 1 corners");
    cut.bytes.resize(cut.bytes.size() - 5);
    check_rejected(cut.bytes + "\x03", MeshFormat::ply_binary, "list length 3 is more than");
    ByteWriter ends;
    ends.text(binary_head + "element face 2\nproperty list uchar int vertex_indices\nproperty uchar flags\nend_header\n");
    const size_t body = ends.bytes.size();
    for (int i = 0; i < 6; ++i) ends.put<float>(0.0f);
    ends.put<uint8_t>(3).put<int32_t>(0).put<int32_t>(1).put<int32_t>(1).put<uint8_t>(0);  // face 0 and its flags
    ends.put<uint8_t>(1).put<int32_t>(0);                                                 // face 1 without its flags
    check_rejected(ends.bytes, MeshFormat::ply_binary,
                   "PLY byte offset " + std::to_string(body + 24 + 14 + 5) + ": the file ends in the middle of the data (1 more bytes expected, 0 left)");
}

TEST_CASE("hostile OBJ") {
    check_rejected("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 0\n", MeshFormat::obj, "OBJ line 4: expected a vertex index");
    check_rejected("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n", MeshFormat::obj, "OBJ line 4: vertex index 4 is out of range (the file has 3 vertices)");
    check_rejected("v 0 0 0\nv 1 0 0\nv 0 1 0\nf -1 -2 -4\n", MeshFormat::obj, "relative vertex index -4 reaches before the first vertex");
    check_rejected("v 0 0 0\nv 1 0 0\nf 1 2\n", MeshFormat::obj, "a face with 2 corners");
    check_rejected("v 0 0 0\nf\n", MeshFormat::obj, "a face with 0 corners");
    check_rejected("v 0 0\n", MeshFormat::obj, "needs three coordinates");
    check_rejected("v 0 zero 0\n", MeshFormat::obj, "expected a coordinate, found 'zero'");
    check_rejected("v 0 0 1,5\n", MeshFormat::obj, "expected a coordinate, found '1,5'");
    check_rejected("v 0 0 0\nf 1 1/2 x/3\n", MeshFormat::obj, "found 'x/3'");
    check_rejected("v 0 0 0\nf 1 1 /3\n", MeshFormat::obj, "found '/3'");
    check_rejected("v 0 0 0\nf 1 1 99999999999999\n", MeshFormat::obj, "is too large");
    check_rejected("v 0 0 0\nf 1 1 99999999999999999999999999\n", MeshFormat::obj, "expected a vertex index");
    check_rejected("v 0 0 0\nf 1 1 -9223372036854775808\n", MeshFormat::obj, "reaches before the first vertex");
    const MeshData nan = read_ok("v nan inf -inf\n", MeshFormat::obj);
    CHECK(std::isnan(nan.positions[0]));
    CHECK(std::isinf(nan.positions[1]));
}

TEST_CASE("hostile OFF") {
    check_rejected("", MeshFormat::off, "the file is empty");
    check_rejected("# only a comment\n", MeshFormat::off, "the file is empty");
    check_rejected("PLY\n", MeshFormat::off, "expected the keyword 'OFF', found 'PLY'");
    check_rejected("4OFF\n", MeshFormat::off, "expected the keyword 'OFF'");
    check_rejected("OFF BINARY\n", MeshFormat::off, "binary OFF is not supported");
    check_rejected("OFF\n", MeshFormat::off, "ends before the vertex and face counts");
    check_rejected("OFF\n-1 0 0\n", MeshFormat::off, "non-negative integers");
    check_rejected("OFF\n3\n", MeshFormat::off, "non-negative integers");
    check_rejected("OFF\n5000000000 1 0\n0 0 0\n", MeshFormat::off, "at most 4294967294");
    const auto start = std::chrono::steady_clock::now();
    check_rejected("OFF\n4000000000 4000000000 0\n0 0 0\n", MeshFormat::off, "OFF line 3: the file ends after 1 of 4000000000 vertices");
    check_rejected("OFF\n1 4000000000 0\n0 0 0\n", MeshFormat::off, "the file ends after 0 of 4000000000 faces");
    CHECK(seconds_since(start) < 1.0);
    const std::string three = "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n";
    check_rejected(three + "3 0 1 3\n", MeshFormat::off, "OFF line 6: vertex index 3 is out of range (the file has 3 vertices)");
    check_rejected(three + "3 0 1 -1\n", MeshFormat::off, "vertex index -1 is out of range");
    check_rejected(three + "2 0 1\n", MeshFormat::off, "a face with 2 corners");
    check_rejected(three + "5 0 1 2\n", MeshFormat::off, "declares 5 corners but lists 3");
    check_rejected(three + "3 0 1 x\n", MeshFormat::off, "expected a vertex index, found 'x'");
    check_rejected(three + "three 0 1 2\n", MeshFormat::off, "expected the number of corners");
    check_rejected("OFF\n1 0 0\n0 0\n", MeshFormat::off, "needs three coordinates");
}

TEST_CASE("hostile XYZ") {
    check_rejected("1 2 3\n4 5\n", MeshFormat::xyz, "XYZ line 2: a point needs three coordinates");
    check_rejected("x y z\n1 2 3\n", MeshFormat::xyz, "XYZ line 1: expected a coordinate, found 'x'");
    check_rejected("1 2 3\n5\n", MeshFormat::xyz, "XYZ line 2: a point needs three coordinates");
    check_rejected("-5\n1 2 3\n", MeshFormat::xyz, "XYZ line 1: a point needs three coordinates");
}

TEST_CASE("hostile STL") {
    check_rejected("short", MeshFormat::stl, "too short for a binary STL");
    std::string lying(84, ' ');
    lying[80] = '\x40';
    lying[81] = '\x42';
    lying[82] = '\x0f';
    lying[83] = '\0';  // a million triangles in 184 bytes
    check_rejected(lying + std::string(100, '\0'), MeshFormat::stl, "declares 1000000 triangles, but the file holds only 2");
    check_rejected("solid x\nfacet\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nvertex 1 1 1\nendfacet\nendsolid\n", MeshFormat::stl,
                   "STL line 6: a facet with more than three vertices");
    check_rejected("solid x\nfacet\nvertex 0 0 0\nvertex 1 0 0\nendfacet\nendsolid\n", MeshFormat::stl, "without exactly three vertices");
    check_rejected("solid x\nfacet\nvertex 0 0 0\n", MeshFormat::stl, "ends inside a facet");
    check_rejected("solid x\nvertex 0 0 0\n", MeshFormat::stl, "'vertex' outside a facet");
    check_rejected("solid x\nfacet\nvertex 0 0 zero\n", MeshFormat::stl, "needs three coordinates");
    check_rejected("solid x\nfacet\nfacet\n", MeshFormat::stl, "'facet' inside a facet");
}

TEST_CASE("text that turns to binary data fails at the first line of it, read from a buffer or a file") {
    const std::string garbage = std::string("\x7f" "ELF\x02\x01\x01", 7) + std::string(9, '\0') + "\xff\xfe\nmore\n";
    const std::string ply_head = "ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\nproperty float y\nproperty float z\nend_header\n";
    const struct {
        MeshFormat format;
        const char* extension;
        std::string good_start;
        const char* expected;
    } cases[] = {
        {MeshFormat::xyz, ".xyz", "1 2 3\n4 5 6\n", "XYZ line 3: binary data (a zero byte) where text was expected"},
        {MeshFormat::obj, ".obj", "# made by hand\nv 0 0 0\nv 1 0 0\n", "OBJ line 4: binary data"},
        {MeshFormat::off, ".off", "OFF\n3 1 0\n0 0 0\n", "OFF line 4: binary data"},
        {MeshFormat::ply_ascii, ".ply", ply_head + "0 0 0\n", "PLY line 9: binary data"},
        {MeshFormat::stl, ".stl", "solid x\nfacet normal 0 0 1\n", "STL line 3: binary data"},
    };
    for (const auto& c : cases) {
        CAPTURE(c.extension);
        const std::string bytes = c.good_start + garbage;
        check_rejected(bytes, c.format, c.expected);
        // A file says the same, after its path.
        const std::string path = write_temp_file(std::string("garbage") + c.extension, bytes);
        MeshData from_buffer, from_file;
        const IoStatus buffer_status = read_mesh_buffer(bytes.data(), bytes.size(), c.format, from_buffer);
        const IoStatus file_status = read_mesh(path, from_file);
        CHECK(file_status.message == path + ": " + buffer_status.message);
        std::remove(path.c_str());
    }
}

TEST_CASE("a line without end fails at the line limit") {
    check_rejected("1 2 3\n" + std::string(LineReader::DEFAULT_MAX_LINE_BYTES + 1, '7'), MeshFormat::xyz,
                   "XYZ line 2: a line longer than 16777216 bytes");
    check_rejected("ply\n" + std::string((1 << 20) + 1, 'c'), MeshFormat::ply_binary, "PLY header line 2: a line longer than 1048576 bytes");
}

TEST_CASE("endless zero bytes from a pipe fail at once, with little read") {
    if (!HAVE_FIFOS) return;
    const struct {
        const char* name;
        const char* expected;
    } cases[] = {
        {"zeros.ply", "PLY header line 1: the file does not begin with the line 'ply'"},
        {"zeros.xyz", "XYZ line 1: binary data"},
        {"zeros.obj", "OBJ line 1: binary data"},
        {"zeros.off", "OFF line 1: binary data"},
    };
    for (const auto& c : cases) {
        CAPTURE(c.name);
        const FifoRead read = read_endless_fifo(c.name, "", '\0');
        CHECK_FALSE(read.status.ok);
        CHECK(read.status.message.find(c.expected) != std::string::npos);
        CHECK(read.bytes_written < (4 << 20));
    }
    // Good lines first: the first line of zeros is named.
    const FifoRead points = read_endless_fifo("points.xyz", "1 2 3\n4 5 6\n", '\0');
    CHECK(points.status.message.find("XYZ line 3: binary data") != std::string::npos);
    CHECK(points.bytes_written < (4 << 20));
    // Text without a line break stops at the line limit.
    const FifoRead sevens = read_endless_fifo("sevens.xyz", "1 2 3\n", '7');
    CHECK(sevens.status.message.find("XYZ line 2: a line longer than 16777216 bytes") != std::string::npos);
    CHECK(sevens.bytes_written < (40 << 20));
}

TEST_CASE("binary formats from a pipe read what their header declares and no more") {
    if (!HAVE_FIFOS) return;
    const MeshData mesh = float_exact_mesh();
    for (const auto& format_and_name :
         {std::pair{MeshFormat::stl, "mesh.stl"}, std::pair{MeshFormat::ply_binary, "mesh.ply"}}) {
        // Not a structured binding: clang before 16 does not let CAPTURE's lambda see one.
        const auto [format, name] = format_and_name;
        CAPTURE(format_and_name.second);
        std::string bytes;
        REQUIRE(write_mesh_buffer(mesh, format, bytes).ok);
        const FifoRead read = read_endless_fifo(name, bytes, '\0');
        INFO(read.status.message);
        CHECK(read.status.ok);
        CHECK(triangle_corners(read.mesh) == triangle_corners(mesh));
        CHECK(read.bytes_written < (4 << 20));
    }
}

TEST_CASE("/dev/zero is refused at once by the text formats and is an empty binary STL") {
    if (!std::filesystem::exists("/dev/zero")) return;
    const std::string directory = temp_path("devices");
    std::filesystem::create_directory(directory);
    for (const char* extension : {".ply", ".xyz", ".obj", ".off", ".stl"}) {
        CAPTURE(extension);
        const std::string path = directory + "/zero" + extension;
        std::filesystem::create_symlink("/dev/zero", path);
        MeshData mesh;
        const IoStatus status = read_mesh(path, mesh);
        if (std::string(extension) == ".stl") {
            CHECK(status.ok);  // 80 header bytes and a count of 0 triangles
            CHECK(mesh.triangle_count() == 0);
        } else {
            CHECK_FALSE(status.ok);
            const bool named = status.message.find("binary data") != std::string::npos ||
                               status.message.find("does not begin with the line 'ply'") != std::string::npos;
            CHECK(named);
        }
    }
    std::filesystem::remove_all(directory);
}

TEST_CASE("STL of unknown size (a pipe) tells ascii from binary by the triangle count's bytes") {
    const std::string ascii = "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\n"
                              "endsolid x\n";
    REQUIRE(ascii.size() > 84);  // its triangle count field is text
    std::string binary;
    REQUIRE(write_mesh_buffer(float_exact_mesh(), MeshFormat::stl, binary).ok);
    binary.replace(0, 5, "solid");
    for (const std::string& bytes : {ascii, binary}) {
        MeshData at_once, piecewise;
        REQUIRE(read_mesh_buffer(bytes.data(), bytes.size(), MeshFormat::stl, at_once).ok);
        const IoStatus status = read_in_pieces(bytes, MeshFormat::stl, false, piecewise);
        INFO(status.message);
        CHECK(status.ok);
        CHECK(same_mesh(piecewise, at_once));
    }
}

TEST_CASE("every prefix and many corruptions of valid files are handled without crashing") {
    MeshData mesh = float_exact_mesh();
    std::mt19937 random(12345);
    for (MeshFormat format : ALL_FORMATS) {
        CAPTURE(format_name(format));
        std::string bytes;
        REQUIRE(write_mesh_buffer(mesh, format, bytes).ok);
        for (size_t length = 0; length <= bytes.size(); ++length) {
            MeshData out;
            const IoStatus status = read_text(std::string_view(bytes.data(), length), format, out);
            if (!status.ok) CHECK_FALSE(status.message.empty());
            for (uint32_t index : out.triangles) CHECK(index < out.vertex_count());
        }
        for (int trial = 0; trial < 2000; ++trial) {
            std::string corrupted = bytes;
            const int edits = 1 + static_cast<int>(random() % 4);
            for (int e = 0; e < edits; ++e) {
                const size_t at = random() % corrupted.size();
                const char choices[] = {'\0', '\xff', '-', '9', ' ', '\n', '/', '#', 'e', '.'};
                corrupted[at] = random() % 2 ? static_cast<char>(random()) : choices[random() % sizeof choices];
            }
            MeshData out;
            const IoStatus status = read_text(corrupted, format, out);
            if (!status.ok) CHECK_FALSE(status.message.empty());
            for (uint32_t index : out.triangles) CHECK(index < out.vertex_count());
        }
    }
}

TEST_CASE("random bytes are rejected or read without crashing by every reader") {
    std::mt19937 random(777);
    for (int trial = 0; trial < 300; ++trial) {
        std::string garbage(random() % 400, '\0');
        for (char& c : garbage) c = static_cast<char>(random());
        // Give the header-driven readers a chance to get past their first line.
        if (trial % 3 == 0) garbage = "ply\nformat binary_little_endian 1.0\n" + garbage;
        if (trial % 3 == 1) garbage = "OFF\n" + garbage;
        for (MeshFormat format : ALL_FORMATS) {
            MeshData out;
            const IoStatus status = read_text(garbage, format, out);
            if (!status.ok) CHECK_FALSE(status.message.empty());
            for (uint32_t index : out.triangles) CHECK(index < out.vertex_count());
        }
    }
}

TEST_CASE("reading a one-million-point binary PLY takes well under a second") {
    for (bool as_float : {true, false}) {
        MeshData cloud;
        cloud.positions.resize(3 * 1000000);
        std::mt19937 random(99);
        std::uniform_real_distribution<double> uniform(-1.0, 1.0);
        for (double& value : cloud.positions) value = as_float ? static_cast<float>(uniform(random)) : uniform(random);
        std::string bytes;
        REQUIRE(write_mesh_buffer(cloud, MeshFormat::ply_binary, bytes).ok);
        const auto start = std::chrono::steady_clock::now();
        MeshData back;
        REQUIRE(read_mesh_buffer(bytes.data(), bytes.size(), MeshFormat::ply_binary, back).ok);
        const double seconds = seconds_since(start);
        MESSAGE("1M-point binary PLY (" << (as_float ? "float32" : "float64") << ", " << bytes.size() / 1000000 << " MB) read in "
                                        << seconds << " s");
        CHECK(same_bits(back.positions, cloud.positions));
        if (!SANITIZED) CHECK(seconds < 0.5);
    }
}


// LAS files laid out field by field as the ASPRS specification (1.4 R15) gives them.
namespace {

struct LasPoint {
    int32_t x, y, z;
    uint16_t intensity, red, green, blue;
};

struct LasFile {
    unsigned minor = 2;
    unsigned format = 0;
    double scale[3] = {0.01, 0.01, 0.01};
    double offset[3] = {0, 0, 0};
    std::vector<LasPoint> points;
    size_t record_padding = 0;      // extra bytes after each record
    size_t vlr_bytes = 0;           // bytes between the header and the points
    size_t header_padding = 0;      // bytes after the version's header, counted in the header size
    std::optional<uint64_t> legacy_count;  // default: the count, or 0 in 1.4 formats 6 to 10
    std::optional<uint64_t> count;         // default: the number of points
    std::optional<uint64_t> record_length; // default: the format's length plus record_padding
    std::optional<uint64_t> point_data_offset;
};

bool format_has_gps_time(unsigned format) { return format == 1 || format >= 3; }
bool format_has_colour(unsigned format) { return format == 2 || format == 3 || format == 5 || format == 7 || format == 8 || format == 10; }
bool format_has_waveform(unsigned format) { return format == 4 || format == 5 || format == 9 || format == 10; }

// One record: X Y Z intensity, the format's other fields zero, colour where the format has it.
std::string las_record(const LasFile& file, const LasPoint& point) {
    ByteWriter w;
    w.put(point.x).put(point.y).put(point.z).put(point.intensity);
    const bool extended = file.format >= 6;
    // Returns, flags, classification, user data, scan angle, point source id.
    w.bytes.append(extended ? 8 : 6, '\x05');
    if (format_has_gps_time(file.format)) w.put(1234.5);
    if (format_has_colour(file.format)) w.put(point.red).put(point.green).put(point.blue);
    if (file.format == 8 || file.format == 10) w.put(uint16_t(777));  // near infrared
    if (format_has_waveform(file.format)) w.bytes.append(29, '\x07');
    w.bytes.append(file.record_padding, '\x09');
    return w.bytes;
}

std::string las_bytes(const LasFile& file) {
    const std::string first_record = las_record(file, file.points.empty() ? LasPoint{} : file.points[0]);
    const uint64_t header_size = (file.minor <= 2 ? 227 : file.minor == 3 ? 235 : 375) + file.header_padding;
    const uint64_t count = file.count.value_or(file.points.size());
    const uint64_t legacy = file.legacy_count.value_or(file.minor >= 4 && file.format >= 6 ? 0 : count);
    ByteWriter w;
    w.text("LASF").put(uint16_t(0)).put(uint16_t(0));
    w.bytes.append(16, '\0');  // project GUID
    w.put(uint8_t(1)).put(uint8_t(file.minor));
    w.bytes.append(32, 's');   // system identifier
    w.bytes.append(32, 'g');   // generating software
    w.put(uint16_t(42)).put(uint16_t(2024));
    w.put(uint16_t(header_size));
    w.put(uint32_t(file.point_data_offset.value_or(header_size + file.vlr_bytes)));
    w.put(uint32_t(file.vlr_bytes > 0 ? 1 : 0));
    w.put(uint8_t(file.format));
    w.put(uint16_t(file.record_length.value_or(first_record.size())));
    w.put(uint32_t(legacy));
    for (int r = 0; r < 5; ++r) w.put(uint32_t(0));
    for (double v : file.scale) w.put(v);
    for (double v : file.offset) w.put(v);
    for (int k = 0; k < 6; ++k) w.put(0.0);  // bounds
    if (file.minor >= 3) w.put(uint64_t(0));  // waveform data start
    if (file.minor >= 4) {
        w.put(uint64_t(0)).put(uint32_t(0));  // extended records: start, count
        w.put(count);
        for (int r = 0; r < 15; ++r) w.put(uint64_t(0));
    }
    REQUIRE(w.bytes.size() == header_size - file.header_padding);
    w.bytes.append(file.header_padding, 'h');
    w.bytes.append(file.vlr_bytes, 'v');
    for (const LasPoint& point : file.points) w.bytes += las_record(file, point);
    return w.bytes;
}

const VertexProperty* find_property(const MeshData& mesh, const std::string& name) {
    for (const VertexProperty& property : mesh.properties) {
        if (property.name == name) return &property;
    }
    return nullptr;
}

std::vector<LasPoint> assorted_las_points() {
    return {{0, 0, 0, 0, 0, 0, 0},
            {1, -2, 3, 65535, 65535, 0, 256},
            {std::numeric_limits<int32_t>::max(), std::numeric_limits<int32_t>::min(), 123456789, 17, 1, 2, 3},
            {-98765, 4321, -1, 300, 40000, 50000, 60000}};
}

// Reads `file` and checks every point's coordinates (the integers times scale plus offset, exactly),
// intensity and colour.
void check_las_read_back(const LasFile& file) {
    const MeshData mesh = read_ok(las_bytes(file), MeshFormat::las);
    REQUIRE(mesh.vertex_count() == file.points.size());
    CHECK(mesh.triangles.empty());
    CHECK_FALSE(mesh.has_faces);
    const VertexProperty* intensity = find_property(mesh, "intensity");
    REQUIRE(intensity);
    CHECK(intensity->type == ValueType::uint16);
    const bool colour = format_has_colour(file.format);
    CHECK(mesh.properties.size() == (colour ? 4u : 1u));
    for (size_t i = 0; i < file.points.size(); ++i) {
        const LasPoint& p = file.points[i];
        const int32_t integers[3] = {p.x, p.y, p.z};
        for (size_t k = 0; k < 3; ++k) CHECK(mesh.positions[3 * i + k] == double(integers[k]) * file.scale[k] + file.offset[k]);
        CHECK(intensity->value(i) == p.intensity);
        if (!colour) continue;
        CHECK(find_property(mesh, "red")->value(i) == p.red);
        CHECK(find_property(mesh, "green")->value(i) == p.green);
        CHECK(find_property(mesh, "blue")->value(i) == p.blue);
    }
}

} // namespace

TEST_CASE("LAS 1.2 to 1.4, record formats 0 to 10: exact coordinates, intensity and colour") {
    CHECK(format_from_path("scan.LAS") == MeshFormat::las);
    for (unsigned minor = 2; minor <= 4; ++minor) {
        // Formats 6 to 10 came with LAS 1.4.
        for (unsigned format = 0; format <= (minor == 4 ? 10u : 5u); ++format) {
            CAPTURE(minor);
            CAPTURE(format);
            LasFile file;
            file.minor = minor;
            file.format = format;
            file.points = assorted_las_points();
            file.scale[0] = 0.001, file.scale[1] = 0.25, file.scale[2] = 1e-7;
            file.offset[0] = 500000.0, file.offset[1] = -4.5e6, file.offset[2] = 0.1;
            check_las_read_back(file);
            // Variable length records before the points, extra bytes in each record, a longer header.
            file.vlr_bytes = 54 + 100;
            file.record_padding = 3;
            file.header_padding = 5;
            check_las_read_back(file);
        }
    }
}

TEST_CASE("LAS 1.4 counts its points in 64 bits; the legacy count may be 0 or the same") {
    LasFile file;
    file.minor = 4;
    file.format = 6;
    file.points = assorted_las_points();
    file.legacy_count = 0;
    check_las_read_back(file);
    file.format = 1;
    file.legacy_count = file.points.size();
    check_las_read_back(file);
    file.legacy_count = 3;
    check_rejected(las_bytes(file), MeshFormat::las, "LAS header: the legacy point count 3 differs from the point count 4");
    // Before 1.4 the legacy count is the count.
    file.minor = 3;
    file.legacy_count = std::nullopt;
    check_las_read_back(file);
}

TEST_CASE("LAS: no points, and what follows the points is read past") {
    LasFile file;
    file.format = 3;
    CHECK(read_ok(las_bytes(file), MeshFormat::las).vertex_count() == 0);
    file.points = assorted_las_points();
    const MeshData mesh = read_ok(las_bytes(file) + "waveform data or extended records", MeshFormat::las);
    CHECK(mesh.vertex_count() == 4);
}

TEST_CASE("LAZ is refused with a message saying to decompress it") {
    LasFile file;
    file.format = 3;
    file.points = assorted_las_points();
    std::string bytes = las_bytes(file);
    bytes[104] = static_cast<char>(0x80 | 3);  // LASzip's mark on the record format
    check_rejected(bytes, MeshFormat::las, "LAS header: the points are compressed (LAZ); decompress the file first, e.g. with 'laszip");
    const std::string path = write_temp_file("scan.laz", las_bytes(file));
    MeshData mesh;
    const IoStatus status = read_mesh(path, mesh);
    CHECK_FALSE(status.ok);
    CHECK(status.message == path + ": LAZ files are compressed; decompress it to .las first, e.g. with 'laszip -i FILE.laz -o FILE.las'");
    std::remove(path.c_str());
}

TEST_CASE("hostile LAS headers are refused with a message naming the problem") {
    LasFile good;
    good.minor = 4;
    good.format = 2;
    good.points = assorted_las_points();
    const std::string valid = las_bytes(good);
    check_rejected("", MeshFormat::las, "LAS header: the file does not begin with 'LASF'");
    check_rejected("LASX" + valid.substr(4), MeshFormat::las, "does not begin with 'LASF'");
    check_rejected(valid.substr(0, 100), MeshFormat::las, "LAS header: the file ends after 100 bytes, inside the 227-byte public header block");
    check_rejected(valid.substr(0, 300), MeshFormat::las, "LAS header: the file ends after 300 bytes, inside the 375-byte LAS 1.4 header");
    auto with = [&](auto change) {
        LasFile file = good;
        change(file);
        return las_bytes(file);
    };
    std::string bytes = valid;
    bytes[24] = 2;
    check_rejected(bytes, MeshFormat::las, "LAS header: version 2.4 is not supported (1.0 to 1.4 are)");
    bytes = valid;
    bytes[104] = 11;
    check_rejected(bytes, MeshFormat::las, "LAS header: unknown point data record format 11 (0 to 10 are read)");
    bytes = valid;
    bytes[94] = static_cast<char>(235 & 0xff), bytes[95] = 0;
    check_rejected(bytes, MeshFormat::las, "LAS header: header size 235 is smaller than the 375 bytes of a LAS 1.4 header");
    check_rejected(with([](LasFile& f) { f.record_length = 25; }), MeshFormat::las,
                   "LAS header: point data record length 25 is smaller than the 26 bytes of format 2");
    check_rejected(with([](LasFile& f) { f.point_data_offset = 300; }), MeshFormat::las,
                   "LAS header: the offset to point data 300 lies inside the header (375 bytes)");
    check_rejected(with([](LasFile& f) { f.point_data_offset = 4000000000u; }), MeshFormat::las,
                   "LAS header: the offset to point data 4000000000 is past the end of the file (479 bytes)");
    check_rejected(with([](LasFile& f) { f.count = 5; }), MeshFormat::las,
                   "LAS header: the file declares 5 points of 26 bytes, more than the 104 bytes after the offset to point data hold");
    check_rejected(with([](LasFile& f) { f.count = 4294967295u; }), MeshFormat::las,
                   "LAS header: the file declares 4294967295 points; at most 4294967294 are supported");
    check_rejected(with([](LasFile& f) { f.scale[1] = 0; }), MeshFormat::las, "LAS header: the y scale factor is not a finite non-zero number");
    check_rejected(with([](LasFile& f) { f.offset[2] = std::numeric_limits<double>::infinity(); }), MeshFormat::las,
                   "LAS header: the z offset is not finite");
}

TEST_CASE("a lying LAS count fails fast without allocating for it, and a truncated file names the record") {
    LasFile file;
    file.minor = 4;
    file.format = 6;
    file.points = assorted_las_points();
    file.count = 4294967294u;
    const auto start = std::chrono::steady_clock::now();
    const std::string bytes = las_bytes(file);
    check_rejected(bytes, MeshFormat::las, "LAS header: the file declares 4294967294 points of 30 bytes");
    CHECK(seconds_since(start) < 1.0);
    // Of unknown size (a pipe), the data runs out at the fifth record.
    MeshData mesh;
    const IoStatus status = read_in_pieces(bytes, MeshFormat::las, false, mesh);
    CHECK(status.message == "LAS byte offset 495: the file ends in the middle of point record 4 (30 bytes expected, 0 left)");
    CHECK(mesh.vertex_count() == 0);

    file.count = std::nullopt;
    const std::string valid = las_bytes(file);
    check_rejected(valid.substr(0, valid.size() - 1), MeshFormat::las, "the file declares 4 points of 30 bytes, more than the 119 bytes");
    for (size_t length = 0; length < valid.size(); ++length) {
        MeshData out;
        const IoStatus prefix = read_text(std::string_view(valid.data(), length), MeshFormat::las, out);
        CHECK_FALSE(prefix.ok);
        CHECK_FALSE(prefix.message.empty());
    }
}

TEST_CASE("LAS coordinates past double's range are read and their place named") {
    LasFile file;
    file.points = {{1, 2, 3, 0, 0, 0, 0}, {std::numeric_limits<int32_t>::max(), 0, 0, 0, 0, 0, 0}};
    file.scale[0] = 1e300;
    const MeshData mesh = read_ok(las_bytes(file), MeshFormat::las);
    CHECK(std::isinf(mesh.positions[3]));
    CHECK(mesh.non_finite_at == "byte offset " + std::to_string(227 + 20));
}

TEST_CASE("LAS random corruptions are refused or read without crashing") {
    LasFile file;
    file.minor = 4;
    file.format = 10;
    file.points = assorted_las_points();
    const std::string valid = las_bytes(file);
    std::mt19937 random(2024);
    for (int trial = 0; trial < 3000; ++trial) {
        std::string corrupted = valid;
        for (int e = 0; e < 1 + static_cast<int>(random() % 3); ++e) {
            // Mostly the header, where the sizes and counts are.
            const size_t at = random() % (trial % 2 ? 375 : corrupted.size());
            corrupted[at] = static_cast<char>(random());
        }
        MeshData out;
        const IoStatus status = read_text(corrupted, MeshFormat::las, out);
        if (!status.ok) CHECK_FALSE(status.message.empty());
        for (const VertexProperty& property : out.properties) CHECK(property.size() == out.vertex_count());
    }
}


TEST_CASE("PLY vertex properties of every type are read with their names and types and written back the same") {
    const std::string ascii =
        "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty uchar red\nproperty float y\n"
        "property uchar green\nproperty uchar blue\nproperty uchar alpha\nproperty float z\nproperty float nx\n"
        "property float ny\nproperty float nz\nproperty char c\nproperty short s\nproperty ushort intensity\n"
        "property int i\nproperty uint u\nproperty float confidence\nproperty double quality\n"
        "property list uchar int ignored_list\n"
        "element face 1\nproperty list uchar int vertex_indices\nproperty uchar face_red\nend_header\n"
        "0 255 0 0 0 255 0 0 0 1 -128 -32768 65535 -2147483648 4294967295 0.5 0.1 2 7 7\n"
        "1 1 0 2 3 4 0 0 1 0 127 32767 0 2147483647 0 -1e30 1e-300 0\n"
        "0 10 1 20 30 40 0 1 0 0 0 0 1 0 1 inf -0 1 9\n"
        "3 0 1 2 200\n";
    const MeshData mesh = read_ok(ascii, MeshFormat::ply_ascii);
    REQUIRE(mesh.vertex_count() == 3);
    CHECK(mesh.positions == std::vector<double>{0, 0, 0, 1, 0, 0, 0, 1, 0});
    CHECK(mesh.normals.size() == 9);
    const std::vector<std::pair<std::string, ValueType>> expected = {
        {"red", ValueType::uint8},      {"green", ValueType::uint8},   {"blue", ValueType::uint8},
        {"alpha", ValueType::uint8},    {"c", ValueType::int8},        {"s", ValueType::int16},
        {"intensity", ValueType::uint16}, {"i", ValueType::int32},     {"u", ValueType::uint32},
        {"confidence", ValueType::float32}, {"quality", ValueType::float64}};
    REQUIRE(mesh.properties.size() == expected.size());
    for (size_t p = 0; p < expected.size(); ++p) {
        CHECK(mesh.properties[p].name == expected[p].first);
        CHECK(mesh.properties[p].type == expected[p].second);
        CHECK(mesh.properties[p].size() == 3);
    }
    CHECK(mesh.properties[0].value(0) == 255);
    CHECK(mesh.properties[1].value(1) == 2);
    CHECK(mesh.properties[3].value(2) == 40);
    CHECK(mesh.properties[4].value(0) == -128);
    CHECK(mesh.properties[5].value(1) == 32767);
    CHECK(mesh.properties[6].value(0) == 65535);
    CHECK(mesh.properties[7].value(0) == -2147483648.0);
    CHECK(mesh.properties[8].value(0) == 4294967295.0);
    CHECK(mesh.properties[9].value(1) == -1e30f);
    CHECK(std::isinf(mesh.properties[9].value(2)));
    CHECK(mesh.properties[10].value(0) == 0.1);
    CHECK(mesh.properties[10].value(1) == 1e-300);
    CHECK(std::signbit(mesh.properties[10].value(2)));
    // Every writer that has vertex properties (PLY, both encodings) gives them back bit for bit.
    for (MeshFormat format : {MeshFormat::ply_binary, MeshFormat::ply_ascii}) {
        CAPTURE(format_name(format));
        std::string bytes;
        REQUIRE(write_mesh_buffer(mesh, format, bytes).ok);
        const MeshData back = read_ok(bytes, format);
        CHECK(same_properties(back.properties, mesh.properties));
        CHECK(back.normals == mesh.normals);
        CHECK(back.triangles == mesh.triangles);
    }
    // A big-endian file gives the same values.
    ByteWriter big;
    big.big_endian = true;
    big.text("ply\nformat binary_big_endian 1.0\nelement vertex 1\nproperty double x\nproperty double y\nproperty double z\n"
             "property ushort intensity\nproperty int i\nproperty float confidence\nend_header\n");
    big.put(1.0).put(2.0).put(3.0).put(uint16_t(65534)).put(int32_t(-70000)).put(0.25f);
    const MeshData from_big = read_ok(big.bytes, MeshFormat::ply_binary);
    REQUIRE(from_big.properties.size() == 3);
    CHECK(from_big.properties[0].value(0) == 65534);
    CHECK(from_big.properties[1].value(0) == -70000);
    CHECK(from_big.properties[2].value(0) == 0.25);
}

TEST_CASE("an ascii PLY value that its property's type cannot hold is refused, naming the vertex") {
    const std::string head = "ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\nproperty float y\nproperty float z\n"
                             "property uchar red\nend_header\n0 0 0 255\n";
    check_rejected(head + "1 1 1 256\n", MeshFormat::ply_ascii, "PLY line 10: vertex 1: property 'red' holds 256, not a uchar");
    check_rejected(head + "1 1 1 1.5\n", MeshFormat::ply_ascii, "vertex 1: property 'red' holds 1.5, not a uchar");
    check_rejected(head + "1 1 1 -1\n", MeshFormat::ply_ascii, "vertex 1: property 'red' holds -1, not a uchar");
    check_rejected(head + "1 1 1 nan\n", MeshFormat::ply_ascii, "vertex 1: property 'red' holds nan, not a uchar");
}

TEST_CASE("writers refuse vertex properties that do not fit the mesh or a PLY header") {
    MeshData mesh = float_exact_mesh();
    std::string bytes;
    auto refused = [&](VertexProperty property, const std::string& expected) {
        MeshData with = mesh;
        with.properties = {std::move(property)};
        const IoStatus status = write_mesh_buffer(with, MeshFormat::ply_binary, bytes);
        CHECK_FALSE(status.ok);
        CHECK(status.message == expected);
    };
    VertexProperty red{"red", ValueType::uint8, {1, 2, 3, 4}};
    REQUIRE(write_mesh_buffer(MeshData(mesh), MeshFormat::ply_binary, bytes).ok);
    refused({"red", ValueType::uint8, {1, 2, 3}}, "vertex property 'red' has 3 values for 4 vertices");
    refused({"red", ValueType::uint16, {1, 2, 3, 4}}, "vertex property 'red' has 2 values for 4 vertices");
    refused({"", ValueType::uint8, {1, 2, 3, 4}}, "a vertex property has no name");
    refused({"my red", ValueType::uint8, {1, 2, 3, 4}}, "vertex property 'my red': a name holds no blank or control character");
    refused({"nx", ValueType::uint8, {1, 2, 3, 4}}, "vertex property 'nx': the name is taken");
    MeshData twice = mesh;
    twice.properties = {red, red};
    CHECK(write_mesh_buffer(twice, MeshFormat::ply_binary, bytes).message == "vertex property 'red': the name is taken");
    mesh.properties = {red};
    CHECK(write_mesh_buffer(mesh, MeshFormat::ply_binary, bytes).ok);
}

TEST_CASE("PLY face properties are read per triangle, a polygon's on each triangle of its fan, and written back the same") {
    const std::string ascii =
        "ply\nformat ascii 1.0\nelement vertex 5\nproperty float x\nproperty float y\nproperty float z\n"
        "element face 2\nproperty uchar flags\nproperty list uchar int vertex_indices\nproperty float weight\n"
        "property list uchar int ignored_list\nend_header\n"
        "0 0 0\n1 0 0\n1 1 0\n0 1 0\n2 2 0\n"
        "1 3 0 1 2 0.5 0\n"
        "254 4 0 2 3 4 -2 1 9\n";
    const MeshData mesh = read_ok(ascii, MeshFormat::ply_ascii);
    REQUIRE(mesh.triangle_count() == 3);
    REQUIRE(mesh.face_properties.size() == 2);
    CHECK(mesh.properties.empty());
    CHECK(mesh.face_properties[0].name == "flags");
    CHECK(mesh.face_properties[0].type == ValueType::uint8);
    CHECK(mesh.face_properties[1].name == "weight");
    CHECK(mesh.face_properties[1].type == ValueType::float32);
    const double flags[3] = {1, 254, 254}, weights[3] = {0.5, -2, -2};
    for (size_t t = 0; t < 3; ++t) {
        CHECK(mesh.face_properties[0].value(t) == flags[t]);
        CHECK(mesh.face_properties[1].value(t) == weights[t]);
    }
    for (MeshFormat format : {MeshFormat::ply_binary, MeshFormat::ply_ascii}) {
        CAPTURE(format_name(format));
        std::string bytes;
        REQUIRE(write_mesh_buffer(mesh, format, bytes).ok);
        const MeshData back = read_ok(bytes, format);
        CHECK(same_properties(back.face_properties, mesh.face_properties));
        CHECK(back.triangles == mesh.triangles);
    }
    // Triangles from strips have no values: with a tristrips element too, the face values are left out.
    const std::string with_strips =
        "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
        "element face 1\nproperty list uchar int vertex_indices\nproperty uchar flags\n"
        "element tristrips 1\nproperty list int int vertex_indices\nend_header\n"
        "0 0 0\n1 0 0\n0 1 0\n3 0 1 2 1\n3 0 2 1\n";
    const MeshData stripped = read_ok(with_strips, MeshFormat::ply_ascii);
    CHECK(stripped.triangle_count() == 2);
    CHECK(stripped.face_properties.empty());
}

TEST_CASE("writers refuse face properties that do not fit the triangles or a PLY header") {
    MeshData mesh = float_exact_mesh();
    REQUIRE(mesh.triangle_count() > 0);
    std::vector<unsigned char> one_each(mesh.triangle_count(), 1);
    std::string bytes;
    mesh.face_properties = {{"flags", ValueType::uint8, one_each}};
    CHECK(write_mesh_buffer(mesh, MeshFormat::ply_binary, bytes).ok);
    mesh.face_properties = {{"vertex_indices", ValueType::uint8, one_each}};
    CHECK(write_mesh_buffer(mesh, MeshFormat::ply_binary, bytes).message == "face property 'vertex_indices': the name is taken");
    one_each.push_back(1);
    mesh.face_properties = {{"flags", ValueType::uint8, one_each}};
    CHECK(write_mesh_buffer(mesh, MeshFormat::ply_binary, bytes).message ==
          "face property 'flags' has " + std::to_string(one_each.size()) + " values for " +
              std::to_string(mesh.triangle_count()) + " triangles");
}

TEST_CASE("LAS intensity and colour become ushort PLY properties") {
    LasFile file;
    file.format = 3;
    file.points = assorted_las_points();
    const MeshData mesh = read_ok(las_bytes(file), MeshFormat::las);
    std::string bytes;
    REQUIRE(write_mesh_buffer(mesh, MeshFormat::ply_binary, bytes).ok);
    CHECK(bytes.find("property ushort intensity\nproperty ushort red\nproperty ushort green\nproperty ushort blue\n") !=
          std::string::npos);
    const MeshData back = read_ok(bytes, MeshFormat::ply_binary);
    CHECK(same_bits(back.positions, mesh.positions));
    CHECK(same_properties(back.properties, mesh.properties));
}

#if defined(__unix__) || defined(__APPLE__)
namespace {

std::string file_bytes(const std::string& path) {
    std::FILE* file = std::fopen(path.c_str(), "rb");
    REQUIRE(file);
    std::string bytes;
    char buffer[4096];
    for (size_t got; (got = std::fread(buffer, 1, sizeof buffer, file)) > 0;) bytes.append(buffer, got);
    std::fclose(file);
    return bytes;
}

size_t files_in(const std::string& folder) {
    return static_cast<size_t>(std::distance(std::filesystem::directory_iterator(folder), {}));
}

} // namespace

TEST_CASE("a streamed binary PLY reads back as written, float or double, in pieces of any size") {
    const std::string folder = temp_path("stream");
    REQUIRE(std::filesystem::create_directory(folder));
    const std::vector<double> xyz = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0.5, 0.25, 0.125};
    const std::vector<uint64_t> corners = {0, 2, 1, 0, 1, 3, 1, 2, 4};
    for (bool as_double : {false, true}) {
        CAPTURE(as_double);
        const std::string path = folder + "/mesh.ply";
        PlyStreamWriter writer;
        REQUIRE(writer.open(path, {5, 3, as_double, false}));
        REQUIRE(writer.add_vertices(xyz.data(), 2));
        REQUIRE(writer.add_vertices(xyz.data() + 6, 3));
        REQUIRE(writer.add_triangles(corners.data(), 1));
        REQUIRE(writer.add_triangles(corners.data() + 3, 2));
        REQUIRE(writer.finish());
        MeshData mesh;
        REQUIRE(read_mesh(path, mesh));
        CHECK(mesh.positions == xyz);  // the coordinates are floats: exact either way
        CHECK(std::equal(corners.begin(), corners.end(), mesh.triangles.begin(), mesh.triangles.end()));
        CHECK(file_bytes(path).find(as_double ? "property double x" : "property float x") != std::string::npos);
    }
    std::filesystem::remove_all(folder);
}

TEST_CASE("a streamed PLY past 2^32 vertices numbers corners in 64 bits") {
    const std::string path = temp_path("wide.ply");
    const std::vector<double> xyz = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    const uint64_t corners[] = {2, 1, 0};
    PlyStreamWriter writer;
    REQUIRE(writer.open(path, {3, 1, false, true}));
    REQUIRE(writer.add_vertices(xyz.data(), 3));
    REQUIRE(writer.add_triangles(corners, 1));
    REQUIRE(writer.finish());
    const std::string bytes = file_bytes(path);
    const std::string header_end = "property list uchar uint64 vertex_indices\nend_header\n";
    const size_t body = bytes.find(header_end);
    REQUIRE(body != std::string::npos);
    const size_t face = body + header_end.size() + 3 * 3 * sizeof(float);
    REQUIRE(bytes.size() == face + 1 + 3 * 8);
    CHECK(bytes[face] == 3);
    for (size_t k = 0; k < 3; ++k) {
        uint64_t index = 0;
        for (size_t i = 0; i < 8; ++i) index |= uint64_t(uint8_t(bytes[face + 1 + 8 * k + i])) << (8 * i);
        CHECK(index == corners[k]);
    }
    std::remove(path.c_str());
}

TEST_CASE("a streamed PLY that fails or is abandoned leaves the old file and no temporary") {
    const std::string folder = temp_path("stream_fail");
    REQUIRE(std::filesystem::create_directory(folder));
    const std::string path = folder + "/mesh.ply";
    {
        std::FILE* old = std::fopen(path.c_str(), "wb");
        REQUIRE(old);
        std::fputs("the old file", old);
        std::fclose(old);
    }
    const std::vector<double> xyz = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    const uint64_t corners[] = {0, 1, 2, 0, 1, 3};
    SUBCASE("fewer triangles than declared") {
        PlyStreamWriter writer;
        REQUIRE(writer.open(path, {3, 2, true, false}));
        CHECK(files_in(folder) == 2);  // the temporary beside the target
        REQUIRE(writer.add_vertices(xyz.data(), 3));
        REQUIRE(writer.add_triangles(corners, 1));
        const IoStatus status = writer.finish();
        CHECK_FALSE(status);
        CHECK(status.message.find("1 triangles written of the 3 and 2 declared") != std::string::npos);
    }
    SUBCASE("an index out of range") {
        PlyStreamWriter writer;
        REQUIRE(writer.open(path, {3, 2, true, false}));
        REQUIRE(writer.add_vertices(xyz.data(), 3));
        const IoStatus status = writer.add_triangles(corners, 2);
        CHECK(status.message.find("triangle 1 uses vertex 3 of 3") != std::string::npos);
        CHECK_FALSE(writer.finish());
    }
    SUBCASE("a triangle before the last vertex") {
        PlyStreamWriter writer;
        REQUIRE(writer.open(path, {3, 1, true, false}));
        REQUIRE(writer.add_vertices(xyz.data(), 2));
        CHECK_FALSE(writer.add_triangles(corners, 1));
    }
    SUBCASE("abandoned before finishing") {
        PlyStreamWriter writer;
        REQUIRE(writer.open(path, {3, 1, true, false}));
        REQUIRE(writer.add_vertices(xyz.data(), 3));
    }
    CHECK(file_bytes(path) == "the old file");
    CHECK(files_in(folder) == 1);
    std::filesystem::remove_all(folder);
}
#endif
