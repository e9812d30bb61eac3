#pragma once

#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

// A call with a point argument of a length that does not fit must throw
// std::invalid_argument whose message names the call and the argument
// ("call: argument ...").
template <class Call>
void expect_refused(Call call, const std::string& call_name, const std::string& argument) {
  try {
    call();
    ADD_FAILURE() << "accepted; expected " << call_name << " to refuse " << argument;
  } catch (const std::invalid_argument& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find(call_name + ": " + argument + " "), std::string::npos) << message;
  }
}
