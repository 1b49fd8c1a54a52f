# Applied to every target of ours through dp_warnings; third-party headers are included as SYSTEM.
add_library(dp_warnings INTERFACE)
target_compile_options(dp_warnings INTERFACE -Wall -Wextra -Wno-unused-parameter)
