// SPDX-License-Identifier: BSD-3-Clause
// PCD DATA binary_compressed: the LZF decompressor on hand-assembled streams (literal runs, short
// and long back-references, every corruption it reports), and compressed PCD files made with a
// small LZF compressor written here.
#include <dynobj/io/PcdFile.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>

#include "../src/Lzf.h"
#include "PcdTestFiles.h"

namespace io = dynobj::io;
using pcd_test::expectError;
using pcd_test::raw;
using pcd_test::tmp;
using pcd_test::write;

namespace {

/// A greedy LZF compressor for the tests (brute-force longest match within 8 KiB).
std::string lzf(const std::string& in) {
  std::string out, lit;
  const auto flush = [&] {
    for (std::size_t k = 0; k < lit.size(); k += 32) {
      const std::size_t n = std::min<std::size_t>(32, lit.size() - k);
      out += static_cast<char>(n - 1) + lit.substr(k, n);
    }
    lit.clear();
  };
  for (std::size_t i = 0; i < in.size();) {
    std::size_t len = 0, dist = 0;
    for (std::size_t d = 1; d <= std::min<std::size_t>(i, 8192); d++) {
      std::size_t l = 0;
      while (i + l < in.size() && l < 264 && in[i + l] == in[i + l - d]) l++;
      if (l > len) len = l, dist = d;
    }
    if (len < 3) {
      lit += in[i++];
      continue;
    }
    flush();
    const std::size_t l = len - 2, d = dist - 1;
    out += static_cast<char>((std::min<std::size_t>(l, 7) << 5) | (d >> 8));
    if (l >= 7) out += static_cast<char>(l - 7);
    out += static_cast<char>(d & 0xff);
    i += len;
  }
  flush();
  return out;
}

std::string unlzf(const std::string& in, std::size_t n, std::string* problem = nullptr) {
  std::string out(n, '\0');
  const std::string p =
      io::detail::lzfDecompress(reinterpret_cast<const std::uint8_t*>(in.data()), in.size(),
                                reinterpret_cast<std::uint8_t*>(out.data()), n);
  if (problem) *problem = p;
  return p.empty() ? out : "";
}

}  // namespace

TEST(PcdLzf, HandAssembledLiteralsAndBackReferences) {
  // "abc", back-reference (len 6, dist 3), "X", back-reference (len 19 = 7 + 10 + 2, dist 1).
  const std::string s(
      "\x02"
      "abc"
      "\x80\x02"
      "\x00X"
      "\xE0\x0A\x00",
      11);
  EXPECT_EQ(unlzf(s, 29), "abcabcabcX" + std::string(19, 'X'));
  std::string problem;
  unlzf(std::string("\x20\x05", 2), 3, &problem);
  EXPECT_NE(problem.find("back-reference before the start"), std::string::npos) << problem;
  unlzf(s, 30, &problem);
  EXPECT_NE(problem.find("LZF output is 29 bytes, the header declares 30"), std::string::npos);
  unlzf(s, 20, &problem);
  EXPECT_NE(problem.find("exceeds the declared 20 bytes"), std::string::npos) << problem;
  unlzf(std::string("\x05"
                    "ab",
                    3),
        6, &problem);
  EXPECT_NE(problem.find("ends inside a literal run"), std::string::npos) << problem;
  unlzf(std::string("\x02"
                    "abc\xE0",
                    5),
        20, &problem);
  EXPECT_NE(problem.find("ends inside a back-reference"), std::string::npos) << problem;
  const std::string text = "the quick brown fox, the quick brown fox, the quick brown fox!";
  EXPECT_LT(lzf(text).size(), text.size());
  EXPECT_EQ(unlzf(lzf(text), text.size()), text);
}

TEST(PcdLzf, BinaryCompressedIsFieldMajor) {
  const int n = 300;
  std::string xs, ys, zs, is;  // field-major: all x, then all y, all z, all intensity
  for (int k = 0; k < n; k++) {
    xs += raw(static_cast<float>(k % 7));
    ys += raw(-1.f);
    zs += raw(static_cast<float>(k));
    is += raw<std::uint8_t>(static_cast<std::uint8_t>(k));
  }
  const std::string plain = xs + ys + zs + is, packed = lzf(plain);
  ASSERT_LT(packed.size(), plain.size() / 2);  // back-references were used
  const std::string head = "FIELDS x y z intensity\nSIZE 4 4 4 1\nTYPE F F F U\nWIDTH " +
                           std::to_string(n) + "\nHEIGHT 1\nPOINTS " + std::to_string(n) +
                           "\nDATA binary_compressed\n";
  const auto sizes = [](std::size_t c, std::size_t u) {
    return raw(static_cast<std::uint32_t>(c)) + raw(static_cast<std::uint32_t>(u));
  };
  const auto c = io::readPcd(write("lzf.pcd", head + sizes(packed.size(), plain.size()) + packed));
  ASSERT_EQ(c.cloud.size(), static_cast<std::size_t>(n));
  EXPECT_EQ(c.cloud.x[10], 3.f);
  EXPECT_EQ(c.cloud.y[299], -1.f);
  EXPECT_EQ(c.cloud.z[299], 299.f);
  EXPECT_EQ(c.cloud.intensity[255], 255.f);
  EXPECT_EQ(c.cloud.intensity[256], 0.f);

  const std::string p = tmp("badlzf.pcd");
  write("badlzf.pcd", head + sizes(packed.size() + 1, plain.size()) + packed);
  expectError(p, "compressed size " + std::to_string(packed.size() + 1) + " exceeds the " +
                     std::to_string(packed.size()) + " bytes left in the file");
  write("badlzf.pcd", head + sizes(packed.size(), plain.size() + 4) + packed);
  expectError(p, "uncompressed size " + std::to_string(plain.size() + 4) + " != POINTS");
  write("badlzf.pcd",
        head + sizes(62, plain.size()) + std::string("\x20\x05", 2) + std::string(60, 'z'));
  expectError(p, "back-reference before the start of the output");
  const std::string short_packed = lzf(plain.substr(1));  // one byte short of the declared size
  write("badlzf.pcd", head + sizes(short_packed.size(), plain.size()) + short_packed);
  expectError(p, "the header declares " + std::to_string(plain.size()));
  write("badlzf.pcd", head + sizes(2, plain.size()) + "zz");
  expectError(p, "2 compressed bytes cannot expand to " + std::to_string(plain.size()));
  write("badlzf.pcd", head + "\x01\x02");
  expectError(p, "truncated");
}
