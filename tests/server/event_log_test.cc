#include "server/event_log.h"

#include <string>
#include <vector>

#include "absl/strings/str_cat.h"
#include "gtest/gtest.h"

namespace membrane::server {
namespace {

v1::JobEvent Progress(int i) {
  v1::JobEvent event;
  event.mutable_progress()->set_stage("shrink");
  event.mutable_progress()->set_fraction(i / 100.0);
  event.mutable_progress()->set_line(absl::StrCat("shrink: ", i, "% after ", i, " s"));
  return event;
}

v1::JobEvent Generation(int i) {
  v1::JobEvent event;
  event.mutable_generation()->set_generation(i);
  event.mutable_generation()->set_plate_size(64 >> (i % 6));
  event.mutable_generation()->set_handle_retry(i % 2 == 1);
  return event;
}

std::vector<std::string> Serialized(const std::vector<v1::JobEvent>& events) {
  std::vector<std::string> out;
  for (const v1::JobEvent& e : events) out.push_back(e.SerializeAsString());
  return out;
}

TEST(EventLog, GivesEveryEventBackInOrderFromAnyIndex) {
  EventLog log;
  std::vector<v1::JobEvent> added;
  for (int i = 0; i < 300; ++i) added.push_back(i % 3 == 0 ? Generation(i) : Progress(i));
  added.emplace_back();
  added.back().mutable_stage()->set_stage("surface");
  for (const v1::JobEvent& e : added) log.Append(e);
  EXPECT_EQ(log.size(), added.size());

  std::vector<v1::JobEvent> all;
  log.CopyFrom(0, all);
  EXPECT_EQ(Serialized(all), Serialized(added));

  std::vector<v1::JobEvent> tail = {Progress(-1)};  // appended to, not replaced
  log.CopyFrom(299, tail);
  ASSERT_EQ(tail.size(), 3u);
  EXPECT_EQ(tail[1].SerializeAsString(), added[299].SerializeAsString());
  EXPECT_EQ(tail[2].stage().stage(), "surface");

  std::vector<v1::JobEvent> none;
  log.CopyFrom(added.size(), none);
  log.CopyFrom(added.size() + 5, none);
  EXPECT_TRUE(none.empty());
}

TEST(EventLog, AnEmptyLogGivesNothing) {
  EventLog log;
  std::vector<v1::JobEvent> out;
  log.CopyFrom(0, out);
  EXPECT_TRUE(out.empty());
  EXPECT_EQ(log.size(), 0u);
  EXPECT_EQ(log.bytes(), 0u);
}

}  // namespace
}  // namespace membrane::server
