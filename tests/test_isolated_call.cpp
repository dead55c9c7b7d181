// run_isolated (trac0r/isolated_call.h): work in a forked child whose
// crash, exit, hang or cut-short message becomes an outcome the parent
// reports, and the PLY and glTF import that runs in it.
#include <catch2/catch.hpp>

#include "trac0r/isolated_call.h"
#include "trac0r/scene.h"
#include "trac0r/scene_loader.h"
#include "trac0r/shape.h"

#include <signal.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <new>
#include <stdexcept>
#include <string>
#include <vector>

using trac0r::IsolatedOutcome;
using trac0r::run_isolated;
using Kind = IsolatedOutcome::Kind;

namespace {
int touched_by_the_child = 0;
}  // namespace

TEST_CASE("run_isolated brings back what the work returns", "[isolated]") {
    // Several pipe buffers' worth, with every byte value.
    std::string bytes(3u << 20, '\0');
    for (std::size_t i = 0; i < bytes.size(); ++i) {
        bytes[i] = static_cast<char>(i * 7 + i / 251);
    }
    const IsolatedOutcome out = run_isolated(
        [&] {
            touched_by_the_child = 1;  // the child's copy only
            return bytes;
        },
        60.0);
    REQUIRE(out.kind == Kind::result);
    CHECK(out.payload == bytes);
    CHECK(touched_by_the_child == 0);
    const IsolatedOutcome empty = run_isolated([] { return std::string(); }, 60.0);
    CHECK(empty.kind == Kind::result);
    CHECK(empty.payload.empty());
}

TEST_CASE("run_isolated reports the work's exceptions", "[isolated]") {
    const IsolatedOutcome error = run_isolated(
        []() -> std::string { throw std::runtime_error("m.glb: cannot read mesh: no"); }, 60.0);
    CHECK(error.kind == Kind::error);
    CHECK(error.payload == "m.glb: cannot read mesh: no");
    const IsolatedOutcome memory =
        run_isolated([]() -> std::string { throw std::bad_alloc(); }, 60.0);
    CHECK(memory.kind == Kind::out_of_memory);
    const IsolatedOutcome other =
        run_isolated([]() -> std::string { throw std::logic_error("odd"); }, 60.0);
    CHECK(other.kind == Kind::exception);
    CHECK(other.detail == "odd");
}

TEST_CASE("run_isolated reports a child that crashes, exits or sends nothing", "[isolated]") {
    const IsolatedOutcome segv = run_isolated(
        []() -> std::string {
            raise(SIGSEGV);
            return "not reached";
        },
        60.0);
    CHECK(segv.kind == Kind::crashed);
    CHECK(segv.detail == "SIGSEGV");
    const IsolatedOutcome abrt = run_isolated(
        []() -> std::string {
            std::abort();
        },
        60.0);
    CHECK(abrt.kind == Kind::crashed);
    CHECK(abrt.detail == "SIGABRT");
    const IsolatedOutcome exited = run_isolated(
        []() -> std::string {
            _exit(3);
        },
        60.0);
    CHECK(exited.kind == Kind::exited);
    CHECK(exited.detail == "exit status 3");
    // An orderly exit without the message: cut short.
    const IsolatedOutcome silent = run_isolated(
        []() -> std::string {
            _exit(0);
        },
        60.0);
    CHECK(silent.kind == Kind::broken);
    CHECK(silent.detail == "a message of 0 bytes, under its header's 9");
}

TEST_CASE("run_isolated stops a child that runs past its limit", "[isolated]") {
    const IsolatedOutcome out = run_isolated(
        []() -> std::string {
            for (;;) {
                pause();
            }
        },
        0.2);
    CHECK(out.kind == Kind::timed_out);
}

TEST_CASE("a glTF file that crashes assimp's reader is one error naming it", "[isolated][mesh]") {
    // A null dereference inside assimp 5.2's glTF reader (found by
    // tests/fuzz/fuzz_mesh): it took the program with it.
    const std::string path = TRAC0R_SOURCE_DIR "/tests/fuzz/findings/assimp_gltf_segv.glb";
    try {
        trac0r::load_mesh_parts(path, glm::vec3(0.0f), glm::vec3(0.0f), glm::vec3(1.0f), 0, true,
                                true);
        FAIL("the file loaded");
    } catch (const std::runtime_error& e) {
        CHECK(std::string(e.what()) ==
              path + ": the glTF reader (assimp) crashed on this file (SIGSEGV): it is malformed");
    }
}

TEST_CASE("the mesh import's time limit takes only positive seconds", "[isolated][mesh]") {
    const double before = trac0r::mesh_import_time_limit();
    CHECK(before == 300.0);
    CHECK_THROWS_AS(trac0r::set_mesh_import_time_limit(0.0), std::invalid_argument);
    CHECK_THROWS_AS(trac0r::set_mesh_import_time_limit(-1.0), std::invalid_argument);
    CHECK(trac0r::mesh_import_time_limit() == before);
}

TEST_CASE("run_isolated bounds the child's memory: past it, out_of_memory", "[isolated]") {
    // 256 MB more than the child has at the fork: 64 MB fit, 4 GB do not
    // (the allocation fails, whatever the machine has).
    const std::uint64_t limit = 256u << 20;
    const IsolatedOutcome fits = run_isolated(
        [] {
            std::vector<char> block(64u << 20, 'x');
            return std::string(1, block.back());
        },
        60.0, limit);
    CHECK(fits.kind == IsolatedOutcome::Kind::result);
    CHECK(fits.payload == "x");
    const IsolatedOutcome over = run_isolated(
        [] {
            std::vector<char> block(std::size_t(4) << 30, 'x');
            return std::string(1, block.back());
        },
        60.0, limit);
#if defined(__SANITIZE_ADDRESS__)
    // AddressSanitizer's allocator reports the failed allocation and ends
    // the child (exit status 1) instead of throwing std::bad_alloc.
    CHECK(over.kind == IsolatedOutcome::Kind::exited);
#else
    CHECK(over.kind == IsolatedOutcome::Kind::out_of_memory);
#endif
}

TEST_CASE("with isolation off the work runs here, its outcome as the child's would be",
          "[isolated]") {
    REQUIRE(trac0r::readers_isolated());
    {
        const trac0r::ReaderIsolation off(false);
        CHECK_FALSE(trac0r::readers_isolated());
        touched_by_the_child = 0;
        const IsolatedOutcome out = run_isolated(
            [] {
                touched_by_the_child = 1;  // this process's own: no child
                return std::string("done");
            },
            60.0);
        CHECK(out.kind == Kind::result);
        CHECK(out.payload == "done");
        CHECK(touched_by_the_child == 1);
        touched_by_the_child = 0;
        const IsolatedOutcome error =
            run_isolated([]() -> std::string { throw std::runtime_error("bad file"); }, 60.0);
        CHECK(error.kind == Kind::error);
        CHECK(error.payload == "bad file");
        const IsolatedOutcome memory =
            run_isolated([]() -> std::string { throw std::bad_alloc(); }, 60.0);
        CHECK(memory.kind == Kind::out_of_memory);
        {
            const trac0r::ReaderIsolation on(true);
            CHECK(trac0r::readers_isolated());
        }
        CHECK_FALSE(trac0r::readers_isolated());
    }
    CHECK(trac0r::readers_isolated());
}

TEST_CASE("LoadOptions::isolate_readers off loads a PLY in this process, the same scene",
          "[isolated][mesh]") {
    char dir_template[] = "/tmp/trac0r_isolation_XXXXXX";
    REQUIRE(mkdtemp(dir_template) != nullptr);
    const std::string dir = dir_template;
    {
        std::FILE* f = std::fopen((dir + "/tri.ply").c_str(), "w");
        REQUIRE(f != nullptr);
        std::fputs("ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                   "property float z\nelement face 1\nproperty list uchar int vertex_indices\n"
                   "end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n",
                   f);
        std::fclose(f);
    }
    const std::string json =
        R"({"materials": {"m": {"type": "diffuse", "color": [0.5, 0.5, 0.5]}},
            "shapes": [{"type": "mesh", "file": "tri.ply", "material": "m"}]})";
    trac0r::LoadOptions here;
    here.isolate_readers = false;
    const trac0r::Scene isolated = trac0r::parse_scene(json, "t.json", dir);
    const trac0r::Scene in_process = trac0r::parse_scene(json, "t.json", dir, here);
    CHECK(isolated.triangle_count() == 1);
    CHECK(trac0r::scene_digest(isolated) == trac0r::scene_digest(in_process));
    CHECK(trac0r::readers_isolated());  // the load's setting ends with it
    std::remove((dir + "/tri.ply").c_str());
    rmdir(dir.c_str());
}
