#include "idbench/engine/urdf.h"

#include <gtest/gtest.h>

#include <string>

#include "engine/urdf_test_util.h"

namespace idbench {
namespace {

using namespace urdf_testing;

// ---- Hostile and broken files (issue 14) ----

// Links joined in a loop: refused naming the joints and the line, not a
// stack overflow in the walk from the root (this test crashed with SIGSEGV
// before; the CTest timeout catches a hang).
TEST(UrdfTest, LoopsAreRefusedNamingTheJointsAndTheLine) {
  const std::string chain = BareLink("base") + MassLink("a") + MassLink("b") + Joint("j1", "revolute", "base", "a") +
                            Joint("j2", "revolute", "a", "b");
  // base → a → b → a: a hangs from two joints (line 7 is j3, line 5 is j1).
  ExpectRejected(Robot(chain + Joint("j3", "revolute", "b", "a")),
                 {"<string>:7: joint 'j3': its child link 'a' already hangs from joint 'j1' (line 5)"});
  // a → b → a apart from the root: each link hangs from one joint.
  ExpectRejected(Robot(BareLink("base") + MassLink("a") + MassLink("b") + Joint("j2", "revolute", "a", "b") +
                       Joint("j3", "revolute", "b", "a")),
                 {"<string>:6: joints 'j3', 'j2' form a loop: link 'a' ← 'b' ← 'a'"});
  ExpectRejected(Robot(BareLink("base") + MassLink("a") + Joint("self", "revolute", "a", "a")),
                 {"<string>:4:", "joints 'self' form a loop"});
}

// Issue 35 item 29: a <mimic> of a joint the file lacks, or of itself, is
// refused naming the joint, the element and the line (it was loaded with a
// warning, the joint independent).
TEST(UrdfTest, AMimicOfNoOtherJointIsRefused) {
  const std::string chain = BareLink("base") + MassLink("a") + MassLink("b") + Joint("j1", "revolute", "base", "a");
  ExpectRejected(Robot(chain + Joint("j2", "revolute", "a", "b", kLimit + "<mimic joint=\"j_1\" multiplier=\"2\"/>")),
                 {"<string>:6: joint 'j2': <mimic joint=\"j_1\">: the file has no joint 'j_1' (joints: 'j1', 'j2'); "
                  "name the joint it follows"});
  ExpectRejected(Robot(chain + Joint("j2", "revolute", "a", "b", kLimit + "<mimic joint=\"j2\"/>")),
                 {"<string>:6: joint 'j2': <mimic joint=\"j2\">: a joint cannot mimic itself; name the joint it follows"});
  // Mimics that follow each other round (j2 → j3 → j2) lead nowhere.
  ExpectRejected(Robot(chain + Joint("j2", "revolute", "a", "b", kLimit + "<mimic joint=\"j3\"/>") + MassLink("c") +
                       Joint("j3", "revolute", "b", "c", kLimit + "<mimic joint=\"j2\"/>")),
                 {"<string>:6: joint 'j2': <mimic joint=\"j3\">: joints 'j2', 'j3' mimic each other in a loop"});
  // A mimic of another joint still loads (with its warning).
  EXPECT_EQ(LoadUrdfString(Robot(chain + Joint("j2", "revolute", "a", "b", kLimit + "<mimic joint=\"j1\"/>")))
                .model.n_links(),
            2);
}

// Every number urdfdom reads is one finite number of the right sign, else
// the file is refused naming the element, the attribute, the text and the
// line (urdfdom dropped such elements and loaded the rest, or said "mass must
// be > 0, got 0.000000" for all of them).
TEST(UrdfTest, NumbersMustBeFiniteWithTheirSignNamingTheLine) {
  const std::string links = BareLink("base") + MassLink("a") + Joint("j1", "revolute", "base", "a");
  for (const std::string mass : {"nan", "inf", "1e400", "heavy", "-1", "1 2"}) {
    ExpectRejected(Robot(links + MassLink("b", mass) + Joint("j2", "revolute", "a", "b")),
                   {"<string>:5: link 'b': <mass value>: expected one finite number >= 0, got '" + mass + "'"});
  }
  ExpectRejected(Robot(links + MassLink("b", "1", "0.1 0 0 nan 0 0.1") + Joint("j2", "revolute", "a", "b")),
                 {"<string>:5: link 'b': <inertia iyy>: expected one finite number, got 'nan'"});
  const std::string b = MassLink("b");
  for (const std::string limit : {"effort=\"-5\" velocity=\"2\"", "effort=\"5\" velocity=\"-2\""}) {
    ExpectRejected(Robot(links + b + Joint("j2", "revolute", "a", "b",
                                             "<limit lower=\"-1\" upper=\"1\" " + limit + "/>")),
                   {"<string>:6: joint 'j2': <limit ", ">: expected one finite number >= 0, got '-"});
  }
  ExpectRejected(Robot(links + b + Joint("j2", "revolute", "a", "b", "<axis xyz=\"0 nan 1\"/>" + kLimit)),
                 {"<string>:6: joint 'j2': <axis xyz>: expected 3 finite numbers, got '0 nan 1'"});
  // Geometry urdfdom dropped (so clearance checks never saw it).
  const auto with_collision = [&](const std::string& geometry) {
    return Robot(links + "<link name=\"b\">\n<collision><geometry>" + geometry +
                 "</geometry></collision></link>\n" + Joint("j2", "revolute", "a", "b"));
  };
  ExpectRejected(with_collision("<box size=\"-1 nan 1e308\"/>"),
                 {"<string>:6: link 'b': <box size>: expected 3 finite numbers > 0, got '-1 nan 1e308'"});
  ExpectRejected(with_collision("<box size=\"1 1 0\"/>"), {"<box size>", "> 0"});
  ExpectRejected(with_collision("<cylinder radius=\"nan\" length=\"1\"/>"),
                 {"<string>:6: link 'b': <cylinder radius>: expected one finite number > 0, got 'nan'"});
  ExpectRejected(with_collision("<sphere radius=\"-0.1\"/>"), {"<sphere radius>", "> 0"});
  ExpectRejected(with_collision("<mesh filename=\"m.stl\" scale=\"1 0 1\"/>"), {"<mesh scale>", "not 0"});
}

// What urdfdom cannot parse, even where it loads the rest, refuses the file:
// a <capsule> (not URDF) made urdfdom drop the collision and load the link
// without it, so clearance checks never saw it.
TEST(UrdfTest, AnElementUrdfdomCannotParseRefusesTheFile) {
  ExpectRejected(Robot(BareLink("base") +
                       "<link name=\"a\"><inertial><mass value=\"1\"/><inertia ixx=\"0.1\" ixy=\"0\" ixz=\"0\" "
                       "iyy=\"0.1\" iyz=\"0\" izz=\"0.1\"/></inertial><collision><geometry><capsule radius=\"1\" "
                       "length=\"1\"/></geometry></collision></link>\n" +
                       Joint("j1", "revolute", "base", "a")),
                 {"not a valid URDF (Unknown geometry type 'capsule')"});
}

// Text that is not XML says so with a line, and binary is not echoed raw.
TEST(UrdfTest, TextThatIsNotXmlIsNamedWithItsLine) {
  ExpectRejected(std::string("\x00\x01\x02 binary", 10), {"not XML: a NUL byte at offset 0 (a binary file?)"});
  ExpectRejected("solid cube\nfacet normal", {"not XML: no element in it; it starts with 'solid cube\\nfacet normal'"});
  ExpectRejected("<robot name=\"r\">\n<link name=\"a\">\n</robot>", {"not XML (line 3"});
  ExpectRejected("<world/>", {"root element is not <robot>, got <world>"});
  // Text that is not UTF-8 (a cut sequence at the end made TinyXML read past
  // the text: found by tests/fuzz/urdf_fuzzer).
  ExpectRejected("<robot name=\"r\">\n<link name=\"a\xce", {"<string>:2: not a valid URDF: byte 0xce at offset 30 is not UTF-8"});
  // A link name with control bytes is echoed escaped.
  ExpectRejected(Robot("<link name=\"a&#1;b\"><inertial><mass value=\"nan\"/></inertial></link>\n"),
                 {"link 'a\\x01b'"});
}

}  // namespace
}  // namespace idbench
