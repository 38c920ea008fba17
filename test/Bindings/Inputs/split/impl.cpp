// The function bindings.cpp registers.
int tripled(int X) { return 3 * X; }
