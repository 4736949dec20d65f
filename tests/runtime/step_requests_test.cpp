#include "runtime/step_requests.hpp"

#include <optional>
#include <vector>

#include <gtest/gtest.h>

namespace felt {
namespace {

/// Records what a request was answered with.
struct Answers {
  std::vector<std::uint64_t> steps;  ///< the step of each status, in the order answered
  std::vector<std::string> errors;

  Completion<SceneStatus> next() {
    return [this](std::expected<SceneStatus, RunnerError> answer) {
      if (answer) {
        steps.push_back(answer->step);
      } else {
        errors.push_back(answer.error().message);
      }
    };
  }
};

SceneStatus at(std::uint64_t step) {
  return {step, 0.001 * static_cast<double>(step), true, 1};
}

TEST(StepRequests, EachRequestStartsWhereTheOneBeforeEndsAndIsAnsweredWhenReached) {
  StepRequests requests;
  Answers answers;
  EXPECT_TRUE(requests.empty());
  requests.add(10, 3, answers.next());  // to 13
  requests.add(11, 2, answers.next());  // after the first: to 15, not 13
  EXPECT_FALSE(requests.empty());
  requests.answer_reached(at(12));
  EXPECT_TRUE(answers.steps.empty());
  requests.answer_reached(at(13));
  EXPECT_EQ(answers.steps, std::vector<std::uint64_t>({13}));
  requests.answer_reached(at(14));
  EXPECT_EQ(answers.steps.size(), 1u);
  requests.answer_reached(at(15));
  EXPECT_EQ(answers.steps, std::vector<std::uint64_t>({13, 15}));
  EXPECT_TRUE(requests.empty());
  // once all are answered, a new one starts from the step it is given
  requests.add(20, 1, answers.next());
  requests.answer_reached(at(20));
  EXPECT_EQ(answers.steps.size(), 2u);
  requests.answer_reached(at(21));
  EXPECT_EQ(answers.steps.back(), 21u);
}

TEST(StepRequests, AJumpPastSeveralTargetsAnswersThemAllInOrder) {
  StepRequests requests;
  Answers answers;
  requests.add(0, 1, answers.next());
  requests.add(0, 1, answers.next());
  requests.add(0, 5, answers.next());
  requests.answer_reached(at(2));
  EXPECT_EQ(answers.steps, std::vector<std::uint64_t>({2, 2}));
  EXPECT_FALSE(requests.empty());
}

TEST(StepRequests, CancellingAnswersEveryRequestWithTheReason) {
  StepRequests requests;
  Answers answers;
  requests.add(0, 4, answers.next());
  requests.add(0, 4, answers.next());
  requests.cancel_all("the scene was reset");
  EXPECT_TRUE(requests.empty());
  EXPECT_TRUE(answers.steps.empty());
  EXPECT_EQ(answers.errors, std::vector<std::string>(2, "the scene was reset"));
  requests.answer_reached(at(100));
  EXPECT_TRUE(answers.steps.empty());
}

}  // namespace
}  // namespace felt
