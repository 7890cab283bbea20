// The job-id format both ends agree on (proto/job_routing.h).
#include "proto/job_routing.h"

#include <gtest/gtest.h>

namespace membrane {
namespace {

TEST(JobRoutingTest, ReplicaNamesAreDnsLabels) {
  EXPECT_TRUE(IsReplicaName("membraned-0"));
  EXPECT_TRUE(IsReplicaName("a"));
  EXPECT_TRUE(IsReplicaName(std::string(63, 'x')));
  EXPECT_FALSE(IsReplicaName(""));
  EXPECT_FALSE(IsReplicaName(std::string(64, 'x')));
  EXPECT_FALSE(IsReplicaName("-a"));
  EXPECT_FALSE(IsReplicaName("a-"));
  EXPECT_FALSE(IsReplicaName("Membraned"));  // a header value a balancer matches as typed
  EXPECT_FALSE(IsReplicaName("a.b"));        // the id's last '.' must end the name
  EXPECT_FALSE(IsReplicaName("a_b"));
  EXPECT_FALSE(IsReplicaName("a/b"));
}

TEST(JobRoutingTest, IdsCarryTheirReplica) {
  EXPECT_EQ(MakeJobId("", 0x1f), "000000000000001f");
  EXPECT_EQ(MakeJobId("membraned-2", 0xabcdef0123456789), "membraned-2.abcdef0123456789");
  EXPECT_EQ(ReplicaOfJobId(MakeJobId("membraned-2", 7)), "membraned-2");
  EXPECT_EQ(ReplicaOfJobId(MakeJobId("", 7)), "");
  // Not ids of a named replica: nothing to route on.
  EXPECT_EQ(ReplicaOfJobId(""), "");
  EXPECT_EQ(ReplicaOfJobId(".abc"), "");
  EXPECT_EQ(ReplicaOfJobId("Evil Host.abc"), "");
  EXPECT_EQ(ReplicaOfJobId("a.b.c"), "");
}

}  // namespace
}  // namespace membrane
