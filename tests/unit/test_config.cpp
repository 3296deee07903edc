#include <gtest/gtest.h>

#include "tests/unit/input_error.hpp"

#include "core/errors.hpp"
#include "io/config.hpp"
#include "io/text_file.hpp"

using clatter::InputError;
using clatter::io::Config;
using clatter::io::Schema;

namespace {

const Schema& schema() {
  static const Schema s{"test schema",
                        {
                            {"grid.n_cells", std::int64_t{64}, "cells per axis", {2, 4096}},
                            {"grid.dx_m", 0.01, "cell size [m]", {0.0, 10.0, true}},
                            {"run.verbose", false, "chatty"},
                            {"run.mode", std::string("fast"), "mode", {}, {"fast", "exact"}},
                            {"run.label", std::string("demo"), "free text"},
                        }};
  return s;
}

void expect_contains(const std::string& text, std::initializer_list<const char*> parts) {
  for (const char* p : parts) EXPECT_NE(text.find(p), std::string::npos) << "'" << p << "' not in: " << text;
}

}  // namespace

TEST(Config, DefaultsWithoutAnyFile) {
  Config c(schema());
  EXPECT_EQ(c.integer("grid.n_cells"), 64);
  EXPECT_DOUBLE_EQ(c.real("grid.dx_m"), 0.01);
  EXPECT_FALSE(c.boolean("run.verbose"));
  EXPECT_EQ(c.string("run.mode"), "fast");
}

TEST(Config, TomlThenSetOverrides) {
  Config c(schema());
  c.merge_toml("[grid]\nn_cells = 128\ndx_m = 1  # an integer is a fine real\n[run]\nmode = \"exact\"\n", "a.toml");
  EXPECT_EQ(c.integer("grid.n_cells"), 128);
  EXPECT_DOUBLE_EQ(c.real("grid.dx_m"), 1.0);
  c.set("grid.n_cells=256");
  c.set("grid.dx_m = 2.5e-3");
  c.set("run.verbose=true");
  c.set("run.label=\"two words\"");
  c.set("run.label=bare/path.h5");
  EXPECT_EQ(c.integer("grid.n_cells"), 256);
  EXPECT_DOUBLE_EQ(c.real("grid.dx_m"), 2.5e-3);
  EXPECT_TRUE(c.boolean("run.verbose"));
  EXPECT_EQ(c.string("run.label"), "bare/path.h5");
}

TEST(Config, MalformedTomlNamesFileAndLine) {
  Config c(schema());
  auto m = error_of([&] { c.merge_toml("[grid]\nn_cells = 64\ndx_m = = 3\n", "bad.toml"); });
  expect_contains(m, {"bad.toml:3", "malformed TOML"});
  m = error_of([&] { c.merge_toml("[grid\nn_cells = 64\n", "bad2.toml"); });
  expect_contains(m, {"bad2.toml:1", "malformed TOML"});
}

// TOML is UTF-8; toml11 reads out of bounds on some other bytes, so they are refused first
// (tests/fuzz/corpus/fuzz_config/regression-non-utf8-literal-string.toml).
TEST(Config, TextThatIsNotUtf8IsRefusedWithItsLine) {
  Config c(schema());
  expect_contains(error_of([&] { c.merge_toml("[run]\nlabel = 'a\xaf'\n", "bytes.toml"); }),
                  {"bytes.toml:2", "not UTF-8"});
  expect_contains(error_of([&] { c.merge_toml("[run] # \xc0\xaf overlong\n", "overlong.toml"); }), {"overlong.toml:1"});
  c.merge_toml("[run] # caf\xc3\xa9 \xe2\x82\xac \xf0\x9f\x98\x80\nlabel = 'caf\xc3\xa9'\n", "utf8.toml");
  EXPECT_EQ(c.string("run.label"), "caf\xc3\xa9");
}

TEST(Config, UnknownKeySuggestsTheNearestOne) {
  Config c(schema());
  auto m = error_of([&] { c.merge_toml("[grid]\nn_cell = 64\n", "u.toml"); });
  expect_contains(m, {"u.toml:2", "unknown key 'grid.n_cell'", "did you mean 'grid.n_cells'"});
  m = error_of([&] { c.merge_toml("[nonsense]\nx = 1\n", "u.toml"); });
  expect_contains(m, {"unknown key 'nonsense.x'"});
  m = error_of([&] { c.merge_toml("n_cells = 64\n", "u.toml"); });
  expect_contains(m, {"unknown key 'n_cells'", "[section]"});
}

TEST(Config, WrongTypeNamesKeyValueAndExpectation) {
  Config c(schema());
  auto m = error_of([&] { c.merge_toml("[grid]\nn_cells = \"64\"\n", "t.toml"); });
  expect_contains(m, {"t.toml:2", "'grid.n_cells'", "\"64\"", "expected an integer"});
  m = error_of([&] { c.merge_toml("[grid]\nn_cells = 64.0\n", "t.toml"); });
  expect_contains(m, {"'grid.n_cells'", "64.0", "expected an integer"});
  m = error_of([&] { c.merge_toml("[run]\nverbose = 1\n", "t.toml"); });
  expect_contains(m, {"'run.verbose'", "expected a boolean"});
  m = error_of([&] { c.merge_toml("[grid]\ndx_m = [1, 2]\n", "t.toml"); });
  expect_contains(m, {"'grid.dx_m'", "an array", "expected a number"});
}

TEST(Config, OutOfRangeNamesTheRange) {
  Config c(schema());
  auto m = error_of([&] { c.merge_toml("[grid]\ndx_m = -0.01\n", "r.toml"); });
  expect_contains(m, {"r.toml:2", "'grid.dx_m'", "-0.01", "must be in (0, 10]"});
  m = error_of([&] { c.merge_toml("[grid]\ndx_m = 0\n", "r.toml"); });  // exclusive bound
  expect_contains(m, {"must be in (0, 10]"});
  m = error_of([&] { c.merge_toml("[grid]\ndx_m = nan\n", "r.toml"); });
  expect_contains(m, {"nan", "must be"});
  m = error_of([&] { c.merge_toml("[grid]\nn_cells = 1\n", "r.toml"); });
  expect_contains(m, {"must be in [2, 4096]"});
  m = error_of([&] { c.merge_toml("[run]\nmode = \"slow\"\n", "r.toml"); });
  expect_contains(m, {"'run.mode'", "\"slow\"", "must be one of fast, exact"});
}

TEST(Config, BadSetNamesTheOverride) {
  Config c(schema());
  expect_contains(error_of([&] { c.set("grid.n_cells"); }), {"--set 'grid.n_cells'", "expected section.key=value"});
  expect_contains(error_of([&] { c.set("grid.ncells=3"); }), {"unknown key 'grid.ncells'", "grid.n_cells"});
  expect_contains(error_of([&] { c.set("grid.n_cells=abc"); }), {"'grid.n_cells'", "'abc'", "expected an integer"});
  expect_contains(error_of([&] { c.set("grid.n_cells=12x"); }), {"expected an integer"});
  expect_contains(error_of([&] { c.set("grid.n_cells="); }), {"expected an integer"});
  expect_contains(error_of([&] { c.set("grid.dx_m=1e"); }), {"expected a number"});
  expect_contains(error_of([&] { c.set("grid.dx_m=-1"); }), {"'-1'", "must be in (0, 10]"});
  expect_contains(error_of([&] { c.set("run.verbose=yes"); }), {"expected true or false"});
  EXPECT_EQ(c.integer("grid.n_cells"), 64);  // a rejected override changes nothing
}

TEST(Config, PrintedConfigParsesBackToTheSameValues) {
  Config a(schema());
  a.set("grid.dx_m=0.1");  // not exactly representable: must survive the round trip
  a.set("run.label=say \"hi\"");
  a.set("grid.n_cells=3");
  Config b(schema());
  b.merge_toml(a.to_toml(), "printed");
  EXPECT_EQ(b.real("grid.dx_m"), 0.1);
  EXPECT_EQ(b.string("run.label"), "say \"hi\"");
  EXPECT_EQ(b.to_toml(), a.to_toml());
}

TEST(Config, SchemaDefaultsMustRespectTheirRanges) {
  Schema bad{"bad", {{"a.b", 0.0, "zero is excluded", {0.0, 1.0, true}}}};
  EXPECT_THROW(Config{bad}, std::logic_error);
}

TEST(Config, MissingFileIsAnInputError) {
  auto m = error_of([] { clatter::io::read_text_file("/nonexistent/clatter.toml"); });
  expect_contains(m, {"/nonexistent/clatter.toml", "cannot open"});
}

TEST(Config, ListsOfNumbersAndOfPoints) {
  Schema s{"lists",
           {{"a.points_m", clatter::io::RealList{1, 0, 0}, "points [m]", {-5.0, 5.0}, {}, 3},
            {"a.fields", clatter::io::RealList{1, 2}, "field indices", {1, 6}}}};
  Config c(s);
  c.merge_toml("[a]\npoints_m = [[1, 2, 3], [0.5, -1, 2]]\nfields = [3]\n", "l.toml");
  EXPECT_EQ(c.reals("a.points_m"), (clatter::io::RealList{1, 2, 3, 0.5, -1, 2}));
  EXPECT_EQ(c.reals("a.fields"), (clatter::io::RealList{3}));
  c.set("a.fields=[4, 5, 6]");
  EXPECT_EQ(c.reals("a.fields"), (clatter::io::RealList{4, 5, 6}));
  expect_contains(error_of([&] { c.merge_toml("[a]\npoints_m = [1, 2, 3]\n", "l.toml"); }),
                  {"l.toml:2", "'a.points_m'", "3-element arrays"});
  expect_contains(error_of([&] { c.merge_toml("[a]\npoints_m = [[1, 2]]\n", "l.toml"); }), {"3-element arrays"});
  expect_contains(error_of([&] { c.merge_toml("[a]\npoints_m = [[1, 2, 9]]\n", "l.toml"); }),
                  {"every element must be in [-5, 5]"});
  expect_contains(error_of([&] { c.set("a.fields=7"); }), {"expected an array of numbers"});
  expect_contains(error_of([&] { c.set("a.fields=[0]"); }), {"every element must be in [1, 6]"});
  Config back(s);
  back.merge_toml(c.to_toml(), "printed");
  EXPECT_EQ(back.to_toml(), c.to_toml());
  EXPECT_NE(c.to_toml().find("points_m = [[1.0, 2.0, 3.0], [0.5, -1.0, 2.0]]"), std::string::npos) << c.to_toml();
}

TEST(Config, ListsOfNames) {
  Schema s{"names",
           {{"a.any", clatter::io::StringList{"x", "y"}, "names"},
            {"a.picked", clatter::io::StringList{"steel"}, "from a set", {}, {"steel", "soil", "wax"}}}};
  Config c(s);
  EXPECT_EQ(c.strings("a.any"), (clatter::io::StringList{"x", "y"}));
  c.merge_toml("[a]\nany = [\"p\", \"q r\"]\npicked = [\"soil\", \"wax\"]\n", "n.toml");
  EXPECT_EQ(c.strings("a.any"), (clatter::io::StringList{"p", "q r"}));
  EXPECT_EQ(c.strings("a.picked"), (clatter::io::StringList{"soil", "wax"}));
  c.set("a.picked=steel, wax");  // bare, comma-separated: no shell quoting needed
  EXPECT_EQ(c.strings("a.picked"), (clatter::io::StringList{"steel", "wax"}));
  c.set("a.any=[\"m\"]");
  EXPECT_EQ(c.strings("a.any"), (clatter::io::StringList{"m"}));
  c.set("a.any=[]");
  EXPECT_TRUE(c.strings("a.any").empty());
  expect_contains(error_of([&] { c.merge_toml("[a]\nany = [1, 2]\n", "n.toml"); }),
                  {"n.toml:2", "'a.any'", "expected an array of strings"});
  expect_contains(error_of([&] { c.merge_toml("[a]\nany = \"p\"\n", "n.toml"); }), {"expected an array of strings"});
  expect_contains(error_of([&] { c.merge_toml("[a]\npicked = [\"lava\"]\n", "n.toml"); }),
                  {"n.toml:2", "'lava' is not one of steel, soil, wax"});
  expect_contains(error_of([&] { c.set("a.picked=steel,,wax"); }), {"--set 'a.picked=steel,,wax'", "expected names"});
  expect_contains(error_of([&] { c.set("a.picked=lava"); }), {"'lava' is not one of"});
  c.set("a.any=[\"with \\\"quote\\\"\"]");
  Config back(s);
  back.merge_toml(c.to_toml(), "printed");
  EXPECT_EQ(back.to_toml(), c.to_toml());
  EXPECT_EQ(back.strings("a.any"), (clatter::io::StringList{"with \"quote\""}));
}
