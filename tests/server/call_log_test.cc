// The structured line per call (server/call_log.h): logfmt quoting, code names and outcomes.
#include "server/call_log.h"

#include <string>

#include "gmock/gmock.h"
#include "gtest/gtest.h"

namespace afmesh::server {
namespace {

using ::testing::HasSubstr;

TEST(CallLog, SuccessfulCallIsOneLineOfKeyValuePairs) {
  CallRecord record;
  record.id = 7;
  record.rpc = "MeshVolume";
  record.peer = "ipv4:127.0.0.1:5000";
  record.messages_in = 3;
  record.bytes_in = 412;
  record.points_in = 4;
  record.triangles_in = 4;
  record.seconds = 0.0123;
  record.points_out = 5;
  record.tets_out = 2;
  EXPECT_EQ(format_call_log(record),
            "call id=7 rpc=MeshVolume peer=ipv4:127.0.0.1:5000 messages_in=3 bytes_in=412 "
            "points_in=4 triangles_in=4 seconds=0.012 outcome=ok code=OK points_out=5 tets_out=2 "
            "message=\"\"");
}

// A refusal with a retry hint (every worker taken) is "busy"; one over a limit, which no retry
// cures, is "over_limit", so a dashboard tells load from requests too large for the server.
TEST(CallLog, AResourceRefusalIsBusyWithARetryHintAndOverLimitWithout) {
  CallRecord record;
  record.status = grpc::Status(grpc::StatusCode::RESOURCE_EXHAUSTED, "about 1e10 tetrahedra");
  EXPECT_THAT(format_call_log(record), HasSubstr("outcome=over_limit code=RESOURCE_EXHAUSTED"));
  record.retry_after_ms = 2000;
  EXPECT_THAT(format_call_log(record), HasSubstr("outcome=busy code=RESOURCE_EXHAUSTED"));
}

TEST(CallLog, MessagesAreQuotedAndEscapedSoTheLineStaysOneRecord) {
  CallRecord record;
  record.status = grpc::Status(grpc::StatusCode::INVALID_ARGUMENT,
                               "triangle 3: index 9 \"out\" of range\nsecond line \\ end");
  const std::string line = format_call_log(record);
  EXPECT_THAT(line, HasSubstr("outcome=bad_input code=INVALID_ARGUMENT"));
  EXPECT_THAT(line,
              HasSubstr(R"(message="triangle 3: index 9 \"out\" of range\nsecond line \\ end")"));
  EXPECT_EQ(line.find('\n'), std::string::npos);
  EXPECT_THAT(line, HasSubstr("peer=\"\""));  // empty values are quoted, never dropped
}

TEST(CallLog, OutcomesGroupTheCodes) {
  EXPECT_STREQ(outcome_of(grpc::StatusCode::UNAUTHENTICATED), "refused");
  EXPECT_STREQ(outcome_of(grpc::StatusCode::PERMISSION_DENIED), "refused");
  EXPECT_STREQ(outcome_of(grpc::StatusCode::RESOURCE_EXHAUSTED), "busy");
  EXPECT_STREQ(outcome_of(grpc::StatusCode::RESOURCE_EXHAUSTED, /*retry_hint=*/false),
               "over_limit");
  EXPECT_STREQ(outcome_of(grpc::StatusCode::UNAVAILABLE), "busy");
  EXPECT_STREQ(outcome_of(grpc::StatusCode::CANCELLED), "stopped");
  EXPECT_STREQ(outcome_of(grpc::StatusCode::DEADLINE_EXCEEDED), "stopped");
  EXPECT_STREQ(outcome_of(grpc::StatusCode::FAILED_PRECONDITION), "mesh_failed");
  EXPECT_STREQ(outcome_of(grpc::StatusCode::INTERNAL), "error");
  EXPECT_STREQ(code_name(grpc::StatusCode::UNAUTHENTICATED), "UNAUTHENTICATED");
  EXPECT_STREQ(code_name(grpc::StatusCode::DATA_LOSS), "DATA_LOSS");
}

TEST(CallLog, IdsAreUniqueAndIncreasing) {
  const std::uint64_t first = next_call_id();
  EXPECT_GT(next_call_id(), first);
}

}  // namespace
}  // namespace afmesh::server
