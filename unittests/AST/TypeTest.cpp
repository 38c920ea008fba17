//===- TypeTest.cpp - the types of b-script, unique per context ------------===//
#include "bsc/AST/Type.h"
#include "gtest/gtest.h"

using namespace bsc;

namespace {
TEST(TypeContext, BuiltinsHaveTheirKindAndName) {
  TypeContext Types;
  EXPECT_TRUE(Types.getInt()->isInt());
  EXPECT_TRUE(Types.getInt()->isArithmetic());
  EXPECT_TRUE(Types.getFloat()->isArithmetic());
  EXPECT_FALSE(Types.getBool()->isArithmetic());
  EXPECT_TRUE(Types.getTaskState()->isTaskState());
  EXPECT_EQ(Types.getInt()->getName(), "int");
  EXPECT_EQ(Types.getFloat()->getName(), "float");
  EXPECT_EQ(Types.getBool()->getName(), "bool");
  EXPECT_EQ(Types.getString()->getName(), "string");
}

TEST(TypeContext, ArraysAreUniqueAndNamedAsCDeclaresThem) {
  TypeContext Types;
  const Type *Row = Types.getArray(Types.getFloat(), 3);
  EXPECT_EQ(Row, Types.getArray(Types.getFloat(), 3));
  EXPECT_NE(Row, Types.getArray(Types.getFloat(), 4));
  EXPECT_NE(Row, Types.getArray(Types.getInt(), 3));
  EXPECT_TRUE(Row->isArray());
  EXPECT_EQ(Row->getElement(), Types.getFloat());
  EXPECT_EQ(Row->getExtent(), 3u);
  EXPECT_EQ(Row->getName(), "float[3]");
  // Two arrays of three floats: the outer extent is written first.
  const Type *Matrix = Types.getArray(Types.getArray(Types.getFloat(), 3), 2);
  EXPECT_EQ(Matrix->getName(), "float[2][3]");
  EXPECT_EQ(Matrix->getElement(), Row);
}

TEST(TypeContext, ContextsDoNotShareTypes) {
  TypeContext A, B;
  EXPECT_NE(A.getInt(), B.getInt());
  EXPECT_NE(A.getArray(A.getInt(), 2), B.getArray(B.getInt(), 2));
}
} // namespace
