// The default OpenMP team (apps/common/threads.hpp): the idle cores, never fewer than one, and
// the user's explicit choice (--threads, OMP_NUM_THREADS) always wins.
#include <gtest/gtest.h>

#include "common/threads.hpp"

namespace pa = powderbed::app;

TEST(ThreadTeam, QuietMachineUsesEveryCore) {
  EXPECT_EQ(pa::choose_thread_team(0, 2, 0.05, nullptr).size, 2);
  EXPECT_EQ(pa::choose_thread_team(0, 16, 0.4, nullptr).size, 16);
}

TEST(ThreadTeam, BusyCoresAreLeftToTheirOwners) {
  EXPECT_EQ(pa::choose_thread_team(0, 2, 0.8, nullptr).size, 1);   // one core busy (0.8 rounds to 1)
  EXPECT_EQ(pa::choose_thread_team(0, 16, 5.6, nullptr).size, 10);
  EXPECT_EQ(pa::choose_thread_team(0, 2, 8.1, nullptr).size, 1);   // overloaded: one thread, not zero
}

TEST(ThreadTeam, ExplicitChoicesWin) {
  EXPECT_EQ(pa::choose_thread_team(3, 2, 8.0, nullptr).size, 3);
  EXPECT_EQ(pa::choose_thread_team(3, 2, 8.0, nullptr).reason, "--threads");
  EXPECT_EQ(pa::choose_thread_team(0, 2, 8.0, "2").size, 2);
  EXPECT_EQ(pa::choose_thread_team(0, 2, 8.0, "2").reason, "OMP_NUM_THREADS");
}

TEST(ThreadTeam, UnreadableInputsFallBackToTheIdleRule) {
  EXPECT_EQ(pa::choose_thread_team(0, 4, 1.0, "many").size, 3);  // not a number: ignored
  EXPECT_EQ(pa::choose_thread_team(0, 4, 1.0, "").size, 3);
  EXPECT_EQ(pa::choose_thread_team(0, 0, -1.0, nullptr).size, 1);  // no processor count, no load
}
