#include <cstdio>
int main() { std::puts("caustica: under construction"); return 0; }
