// SPDX-License-Identifier: BSD-3-Clause
#include <dynobj/eval/Report.h>
#include <gtest/gtest.h>

using namespace dynobj;
using namespace dynobj::eval;

TEST(Report, MarkdownTablePrintsUndefinedAsNa) {
  RunResult r;
  r.sequence = "empty";
  r.description = "nothing dynamic";
  r.metrics.add(1, {}, {}, 10);  // no dynamic point anywhere: precision, recall, IoU, F1 undefined
  const std::string t = markdownTable({r});
  EXPECT_NE(t.find("| empty | nothing dynamic | n/a | n/a | n/a | n/a | n/a | 0.000 % | — |"),
            std::string::npos)
      << t;
}
