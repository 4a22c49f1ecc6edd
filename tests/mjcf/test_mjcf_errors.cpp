// A malformed or unbuildable model is a SceneError naming its file, line
// and element, never a crash or a silent default.
#include <fstream>

#include "mjcf_fixture.h"

namespace reeve::test {
namespace {

struct BadModel {
  const char* name;
  const char* xml;
  int line;
  const char* element;   // the element named in the error
  const char* expected;  // part of what the error says was expected
};

const BadModel kBadModels[] = {
    {"not_xml", "<mujoco>\n<worldbody>\n</mujoco>\n", 3, "XML", "well-formed XML"},
    {"not_mujoco", "<robot/>\n", 1, "<robot>", "<mujoco> as the root"},
    {"bad_number", "<mujoco>\n<worldbody>\n<body pos=\"0 0 x\"><freejoint/><geom size=\"1\"/></body>\n</worldbody>\n</mujoco>\n",
     3, "<body>", "pos as finite numbers"},
    {"short_vector", "<mujoco>\n<worldbody>\n<body pos=\"0 0\"><freejoint/><geom size=\"1\"/></body>\n</worldbody>\n</mujoco>\n", 3,
     "<body>", "pos of 3 numbers"},
    {"unknown_site", "<mujoco>\n<worldbody>\n<site name=\"a\"/>\n</worldbody>\n<tendon>\n<spatial>\n<site site=\"a\"/>\n"
                     "<site site=\"b\"/>\n</spatial>\n</tendon>\n</mujoco>\n",
     8, "<site>", "the name of a site"},
    {"massless", "<mujoco>\n<worldbody>\n<body name=\"m\">\n<joint type=\"hinge\"/>\n<geom size=\"1\" mass=\"0\"/>\n</body>\n"
                 "</worldbody>\n</mujoco>\n",
     3, "<body name=\"m\">", "a moving body with mass"},
    {"no_moments", "<mujoco>\n<worldbody>\n<body name=\"p\">\n<freejoint/>\n<inertial mass=\"1\" diaginertia=\"0 0 0\"/>\n"
                   "</body>\n</worldbody>\n</mujoco>\n",
     3, "<body name=\"p\">", "a moving body with moments of inertia > 0"},
    {"not_utf8", "<mujoco>\n<worldbody>\n<body name=\"\xA1\"><freejoint/><geom size=\"1\"/></body>\n</worldbody>\n</mujoco>\n", 3,
     "XML", "UTF-8 text"},
    {"unknown_class", "<mujoco>\n<worldbody>\n<body>\n<freejoint/>\n<geom class=\"nope\" size=\"1\"/>\n</body>\n</worldbody>\n</mujoco>\n",
     5, "<geom>", "a class defined in <default>"},
    {"bad_type", "<mujoco>\n<worldbody>\n<body>\n<freejoint/>\n<geom type=\"torus\" size=\"1\"/>\n</body>\n</worldbody>\n</mujoco>\n",
     5, "<geom>", "a geom type of"},
    {"limited_no_range", "<mujoco>\n<worldbody>\n<body>\n<joint type=\"hinge\" limited=\"true\"/>\n<geom size=\"1\"/>\n</body>\n"
                         "</worldbody>\n</mujoco>\n",
     4, "<joint>", "a range with limited"},
    {"missing_include", "<mujoco>\n<include file=\"nowhere.xml\"/>\n</mujoco>\n", 2, "<include>", "a readable file"},
    {"missing_mesh", "<mujoco>\n<asset>\n<mesh file=\"nowhere.stl\"/>\n</asset>\n<worldbody>\n<body><freejoint/>"
                     "<geom type=\"mesh\" mesh=\"nowhere\"/></body>\n</worldbody>\n</mujoco>\n",
     3, "<mesh>", "a mesh Reeve can read"},
    {"unknown_mesh", "<mujoco>\n<worldbody>\n<body><freejoint/>\n<geom type=\"mesh\" mesh=\"teapot\"/>\n</body>\n</worldbody>\n"
                     "</mujoco>\n",
     4, "<geom>", "the name of a <mesh> asset"},
    {"fitted_mesh", "<mujoco>\n<asset>\n<mesh file=\"part.stl\"/>\n</asset>\n<worldbody>\n<body><freejoint/>\n"
                    "<geom mesh=\"part\"/></body>\n</worldbody>\n</mujoco>\n",
     7, "<geom>", "type=\"mesh\" on a geom that names a mesh"},
    {"msh_mesh", "<mujoco>\n<asset>\n<mesh file=\"part.msh\"/>\n</asset>\n<worldbody>\n<body><freejoint/>"
                 "<geom type=\"mesh\" mesh=\"part\"/></body>\n</worldbody>\n</mujoco>\n",
     3, "<mesh>", "a mesh Reeve can read"},
    {"two_orientations", "<mujoco>\n<worldbody>\n<body euler=\"0 0 0\" quat=\"1 0 0 0\"><freejoint/><geom size=\"1\"/></body>\n"
                         "</worldbody>\n</mujoco>\n",
     3, "<body>", "at most one of quat"},
};

TEST(MjcfErrors, EachNamesFileLineAndElement) {
  for (const BadModel& bad : kBadModels) {
    const auto path = writeModel(bad.name, bad.xml);
    try {
      importMjcf(path);
      ADD_FAILURE() << bad.name << ": imported";
    } catch (const SceneError& e) {
      const std::string what = e.what();
      EXPECT_EQ(e.file(), path.string()) << bad.name;
      EXPECT_EQ(e.line(), bad.line) << bad.name << ": " << what;
      EXPECT_EQ(what.rfind(path.string() + ":" + std::to_string(bad.line) + ": " + bad.element + ": expected ", 0), 0u)
          << bad.name << ": " << what;
      EXPECT_NE(e.expected().find(bad.expected), std::string::npos) << bad.name << ": " << what;
    }
  }
}

// A mesh file that is wrong says where: its own file and line (a face of a
// vertex not yet given), or what is wrong with the solid (a mesh inside
// out, where the compiler is exact; a flat one), at the <mesh> that names it.
TEST(MjcfErrors, MeshFilesSayWhatIsWrongWithThem) {
  // Line 3 is the <mesh>; an exact compiler takes the triangles' sense.
  const auto model = [](const std::string& name, const std::string& obj) {
    writeModel(name + "_mesh", "");
    std::ofstream(std::filesystem::temp_directory_path() / "reeve_mjcf_tests" / (name + ".obj")) << obj;
    return writeModel(name, "<mujoco>\n<compiler exactmeshinertia=\"true\"/><asset>\n<mesh file=\"" + name +
                                ".obj\"/>\n</asset>\n<worldbody>\n<body><freejoint/>"
                                "<geom type=\"mesh\" mesh=\"" + name + "\"/></body>\n</worldbody>\n</mujoco>\n");
  };
  const std::string tetra = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n";
  struct Case {
    std::string name, obj, found;
  };
  for (const Case& c : {Case{"bad_face", tetra + "f 1 3 2\nf 1 2 7\n", "bad_face.obj:6: a vertex number of 1 to 4"},
                        Case{"inside_out", tetra + "f 1 2 3\nf 1 4 2\nf 1 3 4\nf 2 4 3\n", "volume > 0"},
                        Case{"flat", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 3 2\n", "volume > 0"},
                        Case{"no_faces", tetra, "a mesh with triangles"}}) {
    const auto path = model(c.name, c.obj);
    try {
      importMjcf(path);
      ADD_FAILURE() << c.name << ": imported";
    } catch (const SceneError& e) {
      EXPECT_EQ(e.line(), 3) << c.name << ": " << e.what();
      EXPECT_NE(e.found().find(c.found), std::string::npos) << c.name << ": " << e.what();
    }
  }
}

// An <include> is read relative to the model, and an error inside it names
// the included file and its line.
TEST(MjcfErrors, IncludedFilesAreReadAndNamed) {
  const auto part = writeModel("part", "<mujoco>\n<worldbody>\n<body name=\"box\">\n<freejoint/>\n<geom type=\"box\" size=\"1 1 1\" density=\"2\"/>\n"
                                       "</body>\n</worldbody>\n</mujoco>\n");
  const auto whole = writeModel("whole", "<mujoco>\n<include file=\"part.xml\"/>\n</mujoco>\n");
  Scene s = parseScene(importMjcf(whole).scene_json, whole.string());
  EXPECT_NEAR(1.0 / s.world->body(bodyNamed(s, "box")).inv_mass, 16.0, 1e-12);
  const auto broken = writeModel("broken_part", "<mujoco>\n<worldbody>\n\n<body pos=\"1\"/>\n</worldbody>\n</mujoco>\n");
  const auto includer = writeModel("includer", "<mujoco>\n<include file=\"broken_part.xml\"/>\n</mujoco>\n");
  try {
    importMjcf(includer);
    ADD_FAILURE() << "imported";
  } catch (const SceneError& e) {
    EXPECT_EQ(e.file(), broken.string());
    EXPECT_EQ(e.line(), 4);
  }
  // A file that includes itself stops, with an error.
  const auto cycle = writeModel("cycle", "<mujoco>\n<include file=\"cycle.xml\"/>\n</mujoco>\n");
  EXPECT_THROW(importMjcf(cycle), SceneError);
}

}  // namespace
}  // namespace reeve::test

namespace reeve::test {
namespace {

// Bodies nested past the reader's limit are an error, not a stack overflow.
TEST(MjcfErrors, BodiesNestedTooDeepAreRefused) {
  std::string xml = "<mujoco>\n<worldbody>\n";
  for (int i = 0; i < 2000; ++i) xml += "<body><freejoint/><geom size=\"0.1\"/>\n";
  for (int i = 0; i < 2000; ++i) xml += "</body>";
  xml += "\n</worldbody>\n</mujoco>\n";
  const auto path = writeModel("deep", xml);
  try {
    importMjcf(path);
    ADD_FAILURE() << "imported";
  } catch (const SceneError& e) {
    EXPECT_EQ(e.line(), 3 + 1000);  // the 1001st body
    EXPECT_NE(e.expected().find("bodies nested at most 1000 deep"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace reeve::test
