#include <string>
#include <vector>

#include "core/model_state.hpp"
#include "core/state_archive.hpp"
#include "requirements.hpp"

namespace {

struct Sample {
  std::vector<double> numbers;
  std::vector<int> none;  // empty: its data() may be null
  std::vector<std::string> names;
  std::string title;
  long long cycle = 0;
};

template <class A>
void visitState(A& a, Sample& s) {
  a(s.numbers), a(s.none), a(s.names), a(s.title), a(s.cycle);
}

}  // namespace

TEST(StateArchive, WhatIsSavedLoadsBackEqualEmptyVectorsIncluded) {
  VDEC_REQUIREMENTS("REQ-RUN-005");
  Sample in{{1.0, -2.5, 1e300}, {}, {"a", "", "long name"}, "title", 123456789012345LL};
  vdec::StateSaver saver;
  saver(in);
  Sample out{{9.0}, {7, 8}, {"x"}, "other", 0};
  vdec::StateLoader loader(saver.bytes());
  loader(out);
  EXPECT_TRUE(loader.finished());
  EXPECT_EQ(out.numbers, in.numbers);
  EXPECT_TRUE(out.none.empty());
  EXPECT_EQ(out.names, in.names);
  EXPECT_EQ(out.title, in.title);
  EXPECT_EQ(out.cycle, in.cycle);
}

TEST(StateArchive, BytesThatEndEarlyOrClaimTooMuchAreRefused) {
  VDEC_REQUIREMENTS("REQ-RUN-005");
  Sample in{{1.0, 2.0}, {}, {"a"}, "t", 1};
  vdec::StateSaver saver;
  saver(in);
  const std::string bytes = saver.bytes();
  for (std::size_t cut = 0; cut < bytes.size(); ++cut) {
    Sample out;
    vdec::StateLoader loader(std::string_view(bytes).substr(0, cut));
    EXPECT_THROW(loader(out), vdec::StateFormatError) << "cut at " << cut;
  }
  std::string huge = bytes;
  huge[0] = '\xff';  // the first vector's length, now far beyond the bytes there are
  Sample out;
  vdec::StateLoader loader(huge);
  EXPECT_THROW(loader(out), vdec::StateFormatError);
}

TEST(StateArchive, AModelRoundTripsThroughItsVisitList) {
  VDEC_REQUIREMENTS("REQ-RUN-005");
  vdec::Model in;
  in.gravity = {0.0, -9.81};
  in.time = 1.25;
  in.cycle = 42;
  in.jointMaterials.push_back({});
  in.jointMaterials[0].name = "j";
  in.jointMaterials[0].tanFriction = 0.5;
  in.contacts.resize(2);
  in.contacts[1].shearStress = 3.5;
  vdec::StateSaver saver;
  vdec::visitState(saver, in);
  vdec::Model out;
  vdec::StateLoader loader(saver.bytes());
  vdec::visitState(loader, out);
  EXPECT_TRUE(loader.finished());
  EXPECT_EQ(out.cycle, 42);
  EXPECT_EQ(out.time, 1.25);
  EXPECT_EQ(out.gravity.y, -9.81);
  EXPECT_EQ(out.jointMaterials.at(0).name, "j");
  EXPECT_EQ(out.jointMaterials.at(0).tanFriction, 0.5);
  EXPECT_EQ(out.contacts.at(1).shearStress, 3.5);
}
