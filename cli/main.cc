// ltp command line (placeholder while the library grows; replaced by the real CLI).
#include <iostream>
int main() { std::cout << "ltp\n"; return 0; }
