#pragma once

// Runs fn, expecting streak::Error whose message contains `needle` and is one line.

#include "util/error.h"

#include <gtest/gtest.h>

#include <string>

namespace streak::test {

template <class Fn>
void expectErrorContaining(Fn&& fn, const std::string& needle) {
    try {
        fn();
        ADD_FAILURE() << "no Error for " << needle;
    } catch (const Error& e) {
        const std::string message = e.what();
        EXPECT_NE(message.find(needle), std::string::npos) << message;
        EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    }
}

}  // namespace streak::test
