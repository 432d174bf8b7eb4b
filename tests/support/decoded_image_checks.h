#pragma once
// Checks of image decoders against OpenImageIO's own decoding of the same files, shared by the
// codecs' tests and the OpenImageIO plugin's.
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "common/image/image.h"
#include "common/image/image_io.h"

namespace hybridlab::test {

inline std::vector<unsigned char> fileBytes(const std::filesystem::path& p) {
    std::ifstream in(p, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

inline void expectSamePixels(const Image& ours, const Image& theirs) {
    ASSERT_EQ(ours.width(), theirs.width());
    ASSERT_EQ(ours.height(), theirs.height());
    for (int y = 0; y < ours.height(); ++y)
        for (int x = 0; x < ours.width(); ++x)
            for (int c = 0; c < 4; ++c) ASSERT_EQ(ours.at(x, y)[c], theirs.at(x, y)[c]) << "pixel " << x << "," << y << " channel " << c;
}

// Every file in fixtures/files decodes, from the file and from memory (an image in a glTF buffer),
// to fixtures/decoded_by_openimageio/<name>.exr bit for bit; `expectedFiles` catches a lost fixture.
inline void expectEveryFileDecodesAsOpenImageIoDecodedIt(const std::filesystem::path& fixtures, int expectedFiles) {
    int files = 0;
    for (const std::filesystem::directory_entry& e : std::filesystem::directory_iterator(fixtures / "files")) {
        const std::string name = e.path().filename().string();
        SCOPED_TRACE(name);
        ++files;
        EXPECT_NO_THROW(checkImageFile(e.path()));
        const Image ours = readImage(e.path());
        expectSamePixels(ours, readImage(fixtures / "decoded_by_openimageio" / (name + ".exr")));
        const std::vector<unsigned char> bytes = fileBytes(e.path());
        expectSamePixels(readImageFromMemory(bytes.data(), bytes.size(), name), ours);
    }
    EXPECT_EQ(files, expectedFiles) << "fixtures missing from " << fixtures;
}

}  // namespace hybridlab::test
