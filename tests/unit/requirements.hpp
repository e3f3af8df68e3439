#pragma once
// Names the requirement(s) a test shows; written into the JUnit XML as the property
// "requirements", which the traceability audit reads.
#include <gtest/gtest.h>

#define VDEC_REQUIREMENTS(ids) ::testing::Test::RecordProperty("requirements", ids)
