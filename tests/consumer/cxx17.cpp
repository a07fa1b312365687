// Included under C++17 (test Package.HeaderSaysItNeedsCxx20): the header must say what it needs,
// not fail deep inside on a C++20 construct.
#include <sslr/sslr.hpp>
