// verify_<case>: the harness with the case folder's metrics (harness.hpp).
#include "harness.hpp"

int main(int argc, char** argv) {
  return hfdda::verification::run_harness(argc, argv, hfdda::verification::case_definition());
}
