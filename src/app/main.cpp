#include "app/cli.h"

int main(int argc, char** argv) { return hermite::app::runCli(argc, argv); }
