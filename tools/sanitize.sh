#!/usr/bin/env bash
# Every test again, built with clang under AddressSanitizer (leaks included)
# and UndefinedBehaviorSanitizer, in Debug at -O1 (the engine and cables at
# -O2; our asserts and the cable invariant checks after every substep on),
# with bounded libFuzzer runs of the scene loader among the tests. CI's
# second step (.ci/run); README, "Hardening"; DESIGN, "CI time" has the
# timings.
set -euo pipefail
cd "$(dirname "$0")/.."
bash tools/setup.sh --sanitizers
CXX=clang++ cmake -S . -B build-sanitize -DCMAKE_BUILD_TYPE=Debug -DCMAKE_CXX_FLAGS_DEBUG="-O1 -gline-tables-only" \
  -DREEVE_SANITIZE=ON -DREEVE_FUZZ=ON
cmake --build build-sanitize -j2
# A finding stops the test that made it; only the library leak named in
# tests/lsan.supp is forgiven, and the report lists it.
export ASAN_OPTIONS="detect_leaks=1:abort_on_error=1:strict_string_checks=1:detect_stack_use_after_return=1"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
export LSAN_OPTIONS="suppressions=$PWD/tests/lsan.supp:print_suppressions=1"
# Left out here, run in the release phase: tests that take code the shipped
# scenes' whole runs take through the sanitizers already, over long
# simulated spans, to check its accuracy (DESIGN, "CI time": 4 minutes of
# the 7 this phase's tests took). Their names' patterns, joined into one
# regular expression below; no pattern holds a group of its own, since
# CMake's regular expressions take at most 9 (with more the expression
# silently excluded nothing, which the check below catches).
release_only=(
  'Bow\.DrawnSlowly' 'Bow\.TheDrawForce' 'Bow\.Released' 'Bow\.TheScenesOwnDrive' 'Bow\.HeldAtFullDraw'
  'Contacts\.TallStack' 'Contacts\.StackStandsAtEverySplit' 'Contacts\.StackOfFiveBoxes'
  'BothSolvers/Springs\.TrapezoidalSpringKeeps' 'BothSolvers/Springs\.Cantilever'
  'Determinism\.' 'Cli\.EveryShippedScenesCsv' 'Hand\.MoreFlexorLoad' 'Hull\.StackOfFive'
  # The energy ledger's four-budget matrix (issue 28): its bookkeeping in
  # the step runs in every scene's whole run here (Invariants), its watch in
  # the command line's tests.
  'EnergyLedger/EveryShippedSceneAtFourBudgets\.'
  # Issue 28's closed forms at four budgets and both solvers, 14-28 s each
  # here: the capped drive, the ledger's motor and the friction wrap on a
  # hinged wheel (motor_belt, capstan and the crane take that code through
  # the sanitizers whole).
  'HingeDrive\.ACappedMotor' 'EnergyLedger\.AMotorPuts' 'Capstan\.AWrapOnAHingedWheel'
  # The rest of issue 28's, 0.4-4.5 s each in Release (10-40 x that here):
  # a resting stack at four budgets (contacts.json's whole run takes the
  # contact code through), the drive targets' and cable damping's sweeps
  # over budgets and masses.
  'RestingStack\.' 'DriveTargets\.AnAngleDrive' 'DriveTargets\.AVelocityRamp' 'DriveTargets\.ASlide'
  'CableDamping\.LightAndHeavy' 'SolverPrice\.'
  # The generated machines' 32 x 32 cells (10-24 s each here) and their
  # Gauss-Seidel cells but 1 x 1 (the direct cells and that one take the
  # same machines through).
  'EnergyLedger/GeneratedMachineAtFourBudgets\..*32x32'
  'EnergyLedger/GeneratedMachineAtFourBudgets\..*gauss_seidel_1x10'
  'EnergyLedger/GeneratedMachineAtFourBudgets\..*gauss_seidel_10x2'
  # Issue 28's fourth session: the elastic wrap at 10 to 64 substeps and the
  # load hauled into its drum (8 and 10 s here; the capstan's and the span's
  # other tests take that code through).
  'Capstan\.AStickingWrapOnAnElasticCable' 'Spool\.ALoadHauledUpIntoItsDrum'
  # Issue 28's fifth session: the elastic drum's 27 s runs at four budgets
  # and the wrap hauled and lowered at four (110 and 15 s here; the spool,
  # hand and capstan scenes take the winding layers and the stick/slip
  # recheck through whole).
  'Elastic\.ADrumWinds' 'Capstan\.HaulingAndLoweringTraceTheTwoBranches'
  # Issue 28's sixth session: the joint chains' costly cells (5 s in Release
  # for Gauss-Seidel at 32 x 32; their 1 x 1 cells take the same chains
  # through), the ball joint tumbling into its limits and the beads on rods
  # at four budgets (20 s here; the chains take the rail's rows through).
  'EnergyLedger/JointChains\..*direct_10_x_2' 'EnergyLedger/JointChains\..*direct_32_x_32'
  'EnergyLedger/JointChains\..*gauss_seidel_1_x_10' 'EnergyLedger/JointChains\..*gauss_seidel_10_x_2'
  'EnergyLedger/JointChains\..*gauss_seidel_32_x_32'
  'SphericalJoint\.ABodyTumblingIntoItsSwingAndTwistLimits' 'PrismaticJoint\.ABeadOn'
  # Issue 29: the hub machines at many K, the fast jerk at four iteration
  # counts and the stretched span pulled in (10 s here; the rigid star of the
  # bench's tests and the fuzzer's joints on two bodies take the hubs through,
  # every rolling scene the held rolling ends); hilbert2_loose's whole
  # Gauss-Seidel run and the winch reversing over a drum at four budgets (15
  # and 10 s here; hilbert2's run and the capstan's other tests take that
  # code through); the pendulums' 100 periods (the start projection's Atwood
  # test takes its code through) and the gym's 450 landings (its other
  # release tests take the same rows through).
  'Hubs\.' 'SnapTaut\.MoreIterations' 'Cli\.ASpanStartingFarPast'
  'Invariants/EveryShippedScene\.InvariantsHoldAfterEverySubstep/hilbert2_loose_gauss_seidel'
  'Capstan\.AWinchReversingOverAFixedDrum' 'SwingEnergy\.AtThe' 'SwingEnergy\.AnInverted'
  'SwingEnergy\.TheStartProjectionIsTheSame' 'Gym\.AtOneSubstep'
  # Issue 29's fourth session: hilbert3's minute, its braked form (twice
  # 10 s; hilbert2's run takes the warm-started caps through) and the jams at
  # four budgets and four machines (3, 1.4 and 1.6 s in Release; the slider
  # hauled onto its pulley takes the jam through here). The sixth: a wheel
  # driven into a slack span, 96 cases (520 s here, 5 s in Release; the
  # pendulum's peg takes the split through). The seventh: the bow's shot at
  # up to 160 substeps (1 s in Release; its 10 x 10 shot stays here). Issue
  # 30's twelfth: that slack span swept by a ball off its middle, 192 cases
  # (8 s in Release; the peg pendulum past a ball and a hull takes the
  # off-plane split through).
  'Hilbert\.Level3RunForAMinute' 'Hilbert\.Level3Braked' 'Jam\.' 'MergeSplit\.ASlackSpan' 'MergeSplit\.ABallSwept'
  'Bow\.TheUndampedShots'
  # Issue 30's tenth session (a clean clone's sanitizer tests took 559 s
  # here): every shipped scene stepped on one and two threads for the same
  # bits (77 s; the sanitizers find no race, and the pool's stress below and
  # the islands' and batches' own tests take the threads through), and the
  # capped drive's sweep of joints and loads (46 s; crane.json's invariants
  # and the crane's tests take the capped drive through).
  'Islands\.ShippedScenesGiveTheSameBits' 'DriveTargets\.ACappedDrive'
  # Issue 30's fourteenth session: the bow held at full draw at four budgets
  # (0.3 s in Release, above) and the inverted pendulum on a trapezoidal
  # spring, 6000 frames four times (0.7 s, above); the bow's draw and the
  # pendulums' other tests take the same rows through here.
  # Issue 30's eighteenth session (this phase's tests 487 s of wall, 965 s
  # of the two cores): the hand's load, mass and budget sweeps at rest and
  # moving (13 to 22 s each here, 99 s in all; hand.json's whole runs under
  # both solvers and its direct solver's stop take the tendons, limits and
  # Newton's residual through), the crane slewed by a torque-limited drive
  # (20 s; crane.json's runs and the crane's lift take it through), the
  # braced bow at rest (13 s; bow.json's runs), the hoist swinging out of
  # its sheaves' plane under Gauss-Seidel (10 s; the same hoist under the
  # direct solver, and every shipped scene's Gauss-Seidel run, the crane's
  # hoist among them, take that code through) and 1024 cables to one load
  # (8 s; the rigid star's and the tackles' tests take the hubs through).
  'Hand\.TendonExcursion' 'Hand\.AtRestEachJoints' 'Hand\.KilonewtonFlexorLoad' 'Hand\.FeatherweightPhalanges'
  'Hand\.AMovingHandEndsASubstep' 'Hand\.MoreIterationsBringTheRestingHand'
  'CraneScene\.ATorqueLimitedAngleDrive' 'Bow\.BracedItIsAtRest' 'OutOfPlane\.UnderGaussSeidelTheHoist'
  'Junction\.ALoadOn1024Cables'
  # Issue 30's twenty-second session: every shipped scene stepped whole and
  # substep by substep, on one and two threads, a frame and a second a step,
  # for the same bits (195 s here, 4 s in Release; every scene's invariants
  # run above takes the whole steps through, and the other WholeSteps tests
  # the islands stopped for news, the interrupt and the first non-finite).
  # The pattern also takes the same comparison under Gauss-Seidel (0.6 s in
  # Release), which the release phase runs.
  'WholeSteps\.EveryShippedScene'
  # Issue 30's thirtieth session: the segmented rope under the start
  # projection at 32 substeps of 2, 8 and 32 iterations, and under the end
  # for comparison (1.5 s in Release; rope_segments.json's whole run takes
  # its contacts and joints through here, and the swing tests the start
  # projection's rows).
  'RopeSegments\.UnderTheStartProjection'
  # Issue 30's thirty-third session: drives stalled against their limits,
  # 684 cells (its first 252 took 14 s here, all 0.5 s in Release;
  # Rotors.ADriveIntoALimitStops..., one of those cells, takes the fixed
  # caps through here).
  'Rotors\.ADriveIntoALimitPushesWithAllItHasAtEveryBudget'
  # Issue 30's thirty-fourth session: boxes on a ramp either side of the
  # friction angle, 100 runs of 2 s at up to 100 substeps (2.4 s in
  # Release; contacts.json's sliding box and hulls.json's block on a ramp
  # take the level hold through here), and the rocking rod's threshold
  # bisected at six budgets (6.5 s here; the segment rope's rods on their
  # wheel take a single point's second pass through).
  'BoxOnARamp\.' 'RockingRod\.ReeveLetsGo'
  # Issue 30's thirty-fifth session: the boxes on a ramp on a kinematic slab
  # too, standing and tilting (5.3 s in Release, above), two boxes stacked
  # on a ramp at three budgets and boxes on a turntable at five (3 and 1.4
  # s in Release; contacts.json's stack and hulls.json's block take the
  # same friction through here).
  'StackOnARamp\.' 'BoxOnATurntable\.'
  # Issue 30's thirty-ninth session: the crane at 100, 20 and 1 x 1 (40 s
  # here at 100 x 1, 2 s in Release; the generated slider's direct 1 x 1
  # and 1 x 10 ledger cells take the rows held at a bound solved again
  # through here, and the gym's lat bar at the paper's budget the
  # safeguard).
  'CraneScene\.PayingOutAtOneIteration'
  # Issue 30's forty-fifth session: the segment rope's whole runs at its
  # new 100 x 1 (75 and 63 s here, 1 s each in Release), its Atwood
  # acceleration at 60 and 100 x 1 (40 s here) and a ball or a roller
  # rolling off a log at four budgets (19 s here with the ball alone; the
  # rope's start projection test at 32 x 2..32 and the rod turned on a
  # wheel, Collide.*, take the curved contacts through here).
  'Invariants/EveryShippedScene\.InvariantsHoldAfterEverySubstep/rope_segments_'
  'RopeSegments\.AtManySubsteps' 'Contacts\.ABallOrARoller'
  # Issue 30's forty-sixth session: a ball rolling over a table's edge or
  # corner (a box, a hull, a drum), 52 runs at 3000 steps a second (0.7 s
  # in Release; Collide.ASphereOnABoxHullOrCylinder and
  # Hull.TheNearestPoint take the code through here), and the stack placed into the ground and itself at
  # three budgets up to 1000 x 1, both solvers (58 s here; the command
  # line's test of a box placed into the ground and a cube takes
  # settleInitialOverlaps through).
  'Contacts\.ABallOrALogRollsOver' 'InitialOverlaps\.AStackPlaced'
  # Forty-seventh session: bodies across two or three supports at five
  # budgets, both solvers (8 s in Release; the mass and tall-block tests
  # take the friction pools through here, the log in a V-groove at three
  # budgets the support groups; the V at 32 x 32 and 100 x 1 took 50 s).
  'AcrossTwoOrThreeSupports\.ItsSupportsFriction' 'AcrossTwoOrThreeSupports\.UnequalFrictions'
  'AcrossTwoOrThreeSupports\.ALogInAVeeIsWedgedAlike'
  # Forty-eighth session: a box put on a bed of balls at five budgets, both
  # solvers (9 s in Release; the mass and tall-block tests take the pools'
  # floor through here).
  'AcrossTwoOrThreeSupports\.ABoxPutOnABed'
  # Fifty-fifth session (a clean clone's sanitizer tests took 661 s of wall,
  # 1313 s of the two cores): the sweeps over budgets, masses and senses
  # that took 10 to 58 s each here (353 s in all, 0.3 to 3 s each in
  # Release). Each suite's other tests and the shipped scenes' whole runs
  # take the same code through: the rope laced through a plate's holes
  # (pinhole.json, Pinhole.*), the contact rows' rest, pull and mass scaling
  # (the heavier weight's lift-off; contacts.json, elastic_ground.json), the
  # frictionless and pretensioned belts (motor_belt.json, the gripping and
  # eccentric belts), the point sliding round its groove out of plane (the
  # winch swinging out of its sheaves' plane), the MuJoCo samples on floors
  # (the contacts between bodies), the light spool snapped (the heavy load
  # running a light spool out), the capstan's stopping rule (capstan.json),
  # ids and thread counts (every shipped scene's invariants; the pool's
  # stress under ThreadSanitizer; the Atwood islands on two threads; the
  # batch's closed-form test), the gym's stack released (gym.json), the
  # damping ledger (the underdamped load), the box on a belt (the drum
  # swept), the reels' inertia ratios (the reels turned round).
  'Lacing\.' 'ContactRows\.ScalingEveryMass' 'ContactRows\.ALoadSetDown' 'ContactRows\.ALoadPulledAlong'
  'Belts\.AFrictionlessBeltOverCentred' 'Belts\.WithNoPretension' 'Belts\.APretensionThatDoesNotGrip'
  'OutOfPlane\.ATangentPointSlidingRoundItsGroove' 'MjcfPhysics\.SampleModelsOnFloors'
  'Spool\.ALightSpoolSnapped' 'Capstan\.TheDirectSolveEnds' 'Islands\.AnyNumberOfThreads'
  'Islands\.AMachineEndsOnTheSameBits' 'Gym\.ReleasedTheStack' 'CableDamping\.TheLedgerCredits'
  'Kinematic\.ABoxPutOnABelt' 'Reels\.AMotorWindingATape' 'Batch\.EachSceneEnds'
  # The belt frictionless on one wheel and gripping the other, 192 cells
  # (3.6 s in Release; motor_belt.json and the belts' other tests take the
  # runs and the path kernel through here).
  'Belts\.FrictionlessOnOneWheel'
  # The light bar threaded on a rope, 336 cells (3.1 s in Release; the
  # hand's and pinhole scenes' whole runs take a body's points on one run
  # and their line-up through here).
  'Threaded/LightBar\.'
  # Fifty-eighth session: placed knots' spans at rest and lifted, 110 runs
  # (26 s here, 0.3 s in Release; the other LightBead tests, the bead under
  # a ceiling and the chain of knots among them, take the placement
  # through here).
  'LightBead\.APlacedKnotsSpans'
)
long="^($(IFS='|'; echo "${release_only[*]}"))"
all=$(ctest --test-dir build-sanitize -N | grep -o 'Total Tests: [0-9]*')
kept=$(ctest --test-dir build-sanitize -N -E "$long" | grep -o 'Total Tests: [0-9]*')
[ "$kept" != "$all" ] || { echo "tools/sanitize.sh: the release-only list excludes no test ($all)" >&2; exit 1; }
ctest --test-dir build-sanitize --output-on-failure -j2 -E "$long"
# The thread pool (reeve.Batch) under ThreadSanitizer, which cannot share a
# build with AddressSanitizer: a standalone stress program, seconds to build.
clang++ -std=c++20 -O1 -g -fsanitize=thread -Iengine/include tests/tsan/thread_pool_stress.cpp \
  engine/src/thread_pool.cpp -o build-sanitize/thread_pool_stress -pthread
# clang 14's TSan cannot place its shadow memory under some kernels'
# high-entropy address randomization ("unexpected memory mapping"): then
# it runs again without randomization; any other finding fails.
if ! TSAN_OPTIONS="halt_on_error=1" build-sanitize/thread_pool_stress 2> build-sanitize/tsan.log; then
  cat build-sanitize/tsan.log >&2
  grep -q "unexpected memory mapping" build-sanitize/tsan.log
  TSAN_OPTIONS="halt_on_error=1" setarch "$(uname -m)" -R build-sanitize/thread_pool_stress
fi
