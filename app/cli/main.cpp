#include <iostream>

#include <CLI/CLI.hpp>

int main(int argc, char** argv) {
    CLI::App app{"diffphoton: insert virtual objects into photographs with matching light"};
    app.require_subcommand(1);
    CLI11_PARSE(app, argc, argv);
    return 0;
}
