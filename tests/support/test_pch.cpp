// SPDX-License-Identifier: Apache-2.0
// tests/support/test_pch.cpp: no code. Its target (uvms_test_pch, tests/CMakeLists.txt) builds
// the precompiled header that every Catch2 test reuses.
