#include "rover/recording/schema.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace rover::recording {
namespace {

std::size_t Count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t p = text.find(what); p != std::string::npos; p = text.find(what, p + 1)) ++n;
  return n;
}

TEST(ResolveIdl, IncludesFirstEachOnceWithoutDirectives) {
  const std::vector<idl::IdlFile> files = {
      {"a.idl", "#ifndef A\n#define A\nmodule m { struct A { long x; }; };\n#endif\n"},
      {"b.idl", "#ifndef B\n#define B\n#include \"a.idl\"\nmodule m { struct B { A a; }; };\n#endif\n"},
      {"c.idl", "  #include \"a.idl\"\n# include \"b.idl\"\nmodule m { struct C { B b; A a; }; };\n"},
  };
  auto text = ResolveIdl("c.idl", files);
  ASSERT_TRUE(text.ok()) << text.status().message();
  EXPECT_EQ(*text,
            "module m { struct A { long x; }; };\n"
            "module m { struct B { A a; }; };\n"
            "module m { struct C { B b; A a; }; };\n");
}

TEST(ResolveIdl, MissingFilesCyclesAndBadIncludesAreErrors) {
  const std::vector<idl::IdlFile> files = {
      {"a.idl", "#include \"nope.idl\"\n"},
      {"x.idl", "#include \"y.idl\"\n"},
      {"y.idl", "#include \"x.idl\"\n"},
      {"z.idl", "struct Z { long x; };\n#include\n"},
  };
  auto missing = ResolveIdl("a.idl", files);
  EXPECT_EQ(missing.status().code(), StatusCode::kNotFound);
  EXPECT_EQ(missing.status().message(),
            "a.idl includes nope.idl, which is not an IDL file of this build");
  auto cycle = ResolveIdl("x.idl", files);
  EXPECT_NE(cycle.status().message().find("include cycle"), std::string::npos)
      << cycle.status().message();
  auto bad = ResolveIdl("z.idl", files);
  EXPECT_EQ(bad.status().message(), "z.idl:2: #include without a file name");
  EXPECT_EQ(ResolveIdl("q.idl", files).status().message(),
            "q.idl is not an IDL file of this build");
}

TEST(SchemaForType, PoseEstimateIsOneSelfContainedText) {
  auto s = SchemaForType("rover_dl_PoseEstimate");
  ASSERT_TRUE(s.ok()) << s.status().message();
  EXPECT_EQ(s->name, "rover::dl::PoseEstimate");
  EXPECT_EQ(s->text.find('#'), std::string::npos) << "no preprocessor directive may remain";
  EXPECT_EQ(Count(s->text, "struct Header"), 1u);
  EXPECT_LT(s->text.find("struct Header"), s->text.find("struct PoseEstimate"));
  EXPECT_NE(s->text.find("module dl"), std::string::npos);
}

TEST(SchemaForType, DdlTypesCarryTheHardwareFamilyAndCommonOnce) {
  auto s = SchemaForType("rover_ddl_Imu");
  ASSERT_TRUE(s.ok()) << s.status().message();
  EXPECT_EQ(Count(s->text, "struct Header"), 1u);
  EXPECT_NE(s->text.find("module hw"), std::string::npos);  // rover_ddl.idl includes rover_hw.idl
  EXPECT_LT(s->text.find("module hw"), s->text.find("module ddl"));
}

TEST(SchemaForType, AplTypesCarryTheDlDefinitionsTheyUse) {
  // rover_apl.idl includes rover_dl.idl: MobilityCommand uses rover::dl::DrivePrimitive.
  auto s = SchemaForType("rover_apl_MobilityCommand");
  ASSERT_TRUE(s.ok()) << s.status().message();
  EXPECT_EQ(s->name, "rover::apl::MobilityCommand");
  EXPECT_EQ(Count(s->text, "struct Header"), 1u);
  EXPECT_NE(s->text.find("enum DrivePrimitive"), std::string::npos);
  EXPECT_LT(s->text.find("module dl"), s->text.find("module apl"));
}

TEST(SchemaForType, EveryTopicTypeOfTheBuildResolves) {
  ASSERT_FALSE(idl::IdlTopicTypes().empty());
  for (const auto& t : idl::IdlTopicTypes()) {
    auto s = SchemaForType(t.c_name);
    ASSERT_TRUE(s.ok()) << t.c_name << ": " << s.status().message();
    EXPECT_EQ(s->name, t.scoped_name);
    const std::string leaf(t.scoped_name.substr(t.scoped_name.rfind(':') + 1));
    EXPECT_NE(s->text.find("struct " + leaf), std::string::npos) << t.c_name;
    EXPECT_EQ(s->text.find('#'), std::string::npos) << t.c_name;
  }
  EXPECT_EQ(FindTopicType("rover_dl_Nothing").status().code(), StatusCode::kNotFound);
  EXPECT_EQ(SchemaForType("rover_dl_Nothing").status().message(),
            "no @topic type 'rover_dl_Nothing' in this build's IDL files");
}

TEST(NormalizeIdl, CommentsAndLayoutDoNotCount) {
  EXPECT_EQ(NormalizeIdl("module m {  // one\n  struct A { long x; /* why */ };\n};\n"),
            "module m{struct A{long x;};};");
  EXPECT_EQ(NormalizeIdl("struct A {long x;};"), NormalizeIdl("struct A\n{\n long  x ;\n} ;"
                                                              " // trailing"));
  EXPECT_NE(NormalizeIdl("struct A { long x; };"), NormalizeIdl("struct A { double x; };"));
}

}  // namespace
}  // namespace rover::recording
