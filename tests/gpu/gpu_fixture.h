// The fixture every GPU test suite shares: one Runtime per suite with the Vulkan validation layer
// on, and a check after each test that the layer said nothing during it.
#pragma once

#include <gtest/gtest.h>

#include "cli/runtime.h"

namespace rg {

class GpuFixture : public ::testing::Test {
protected:
    static void SetUpTestSuite() {
        RuntimeOptions o;
        o.validation = true;
        auto rt = Runtime::create(o);
        ASSERT_TRUE(rt.has_value()) << rt.error().describe();
        s_runtime = std::move(*rt).release();
    }
    static void TearDownTestSuite() {
        delete s_runtime;
        s_runtime = nullptr;
    }
    void SetUp() override {
        ASSERT_NE(s_runtime, nullptr);
        m_messagesBefore = s_runtime->gpu().validationMessageCount();
    }
    void TearDown() override {
        ASSERT_NE(s_runtime, nullptr);
        EXPECT_EQ(s_runtime->gpu().validationMessageCount(), m_messagesBefore)
            << (s_runtime->gpu().validationMessages().empty() ? "" : s_runtime->gpu().validationMessages().back());
    }
    static Runtime& rt() { return *s_runtime; }

    inline static Runtime* s_runtime = nullptr;
    uint32_t m_messagesBefore = 0;
};

}  // namespace rg
