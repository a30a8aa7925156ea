// A test with a scratch folder of its own for the files a scene names (textures, environments),
// and scenes parsed from text as if their file lay in it.
#pragma once

#include <gtest/gtest.h>

#include <string>

#include "assembly/scene_loader.h"
#include "support/image_files.h"

namespace glint::testing {

class SceneFolderTest : public ::testing::Test {
protected:
    explicit SceneFolderTest(const std::string& name) : folder_(name) {}
    LoadedScene load(const std::string& text) const { return parse_scene(text, folder_.path()); }
    // The loader's message for `text`, or "no error".
    std::string error_of(const std::string& text) const {
        try {
            load(text);
        } catch (const SceneError& e) {
            return e.what();
        }
        return "no error";
    }
    ScratchFolder folder_;
};

}  // namespace glint::testing
