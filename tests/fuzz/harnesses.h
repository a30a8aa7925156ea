// The inputs glint accepts from outside, one entry point per parser, for libFuzzer
// (fuzz_main.cpp) and for the regression test that replays the corpus in the normal build
// (tests/test_fuzz_corpus.cpp). Each harness accepts the parser's own documented error and lets
// anything else escape: an unexpected exception, a crash or a sanitizer report is a finding.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>

namespace glint::fuzz {

// The folder the scene harness resolves mesh references in (the OBJ seed corpus).
std::filesystem::path mesh_folder();
// The folder of presets the request harness loads from (the project's scenes/).
std::filesystem::path scenes_folder();

void scene(const uint8_t* data, size_t size);        // scene JSON -> parse_scene
void obj(const uint8_t* data, size_t size);          // OBJ text -> parse_obj, to_triangles
void partial(const uint8_t* data, size_t size);      // partial file minus its checksum -> decode_partial
void job_request(const uint8_t* data, size_t size);  // POST /render and /jobs body -> parse_job_request
// A GET request's target (/jobs/ID/stream?token=...) -> cpp-httplib's request parsing, as the
// server runs it (path decoding, parse_query_text), then the token check (check_token).
void query(const uint8_t* data, size_t size);
void job_patch(const uint8_t* data, size_t size);  // PATCH /jobs/{id} body -> parse_job_patch
void texture(const uint8_t* data, size_t size);    // an image file -> decode_texture, then lookups

}  // namespace glint::fuzz
