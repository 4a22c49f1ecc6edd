# `reeve bench peers` against MuJoCo as Debian's libmujoco-dev installs it
# (/usr/include/mujoco/mujoco.h, libmujoco.so); included by bench/CMakeLists.txt
# after reeve_bench is defined. Without it, or with REEVE_BENCH_PEERS off,
# the sub-command is built as a stub that says how to get it.
# The package's own CMake config is not used: it requires OpenGL and names
# /usr/include/libqhull_r, neither of which libmujoco-dev depends on, and an
# imported target with a missing include folder stops the configure.
option(REEVE_BENCH_PEERS "Build `reeve bench peers` when MuJoCo (libmujoco-dev) is found" ON)

if(REEVE_BENCH_PEERS)
  find_path(MUJOCO_INCLUDE_DIR mujoco/mujoco.h DOC "Folder holding mujoco/mujoco.h (libmujoco-dev)")
  find_library(MUJOCO_LIBRARY mujoco DOC "MuJoCo's library (libmujoco-dev)")
endif()

if(REEVE_BENCH_PEERS AND MUJOCO_INCLUDE_DIR AND MUJOCO_LIBRARY)
  message(STATUS "reeve bench peers: MuJoCo found (${MUJOCO_LIBRARY})")
  target_sources(reeve_bench PRIVATE ${CMAKE_CURRENT_LIST_DIR}/src/peers.cpp)
  target_include_directories(reeve_bench SYSTEM PRIVATE ${MUJOCO_INCLUDE_DIR})
  target_link_libraries(reeve_bench PRIVATE ${MUJOCO_LIBRARY})
elseif(NOT REEVE_BENCH_PEERS)
  message(STATUS "reeve bench peers: off (REEVE_BENCH_PEERS=OFF)")
  target_sources(reeve_bench PRIVATE ${CMAKE_CURRENT_LIST_DIR}/src/peers_unavailable.cpp)
else()
  message(STATUS "reeve bench peers: not built: MuJoCo not found (apt-get install libmujoco-dev, then re-run cmake)")
  target_sources(reeve_bench PRIVATE ${CMAKE_CURRENT_LIST_DIR}/src/peers_unavailable.cpp)
endif()
