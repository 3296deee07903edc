# ---- the ground bank (docs/ground.md, docs/bank-format.md "Ground bank"): included by
# CMakeLists.txt after bad_inputs.cmake (it uses clatter_error_test and the paths set there).

# End to end on 1 and 2 ranks, interrupted and resumed, merged: one content hash; info; the bank
# read with h5py: layout and the overhead listener's physics (cli/ground_checks.py). No PASS regex:
# the script's exit code decides.
set(ground_dir ${CMAKE_CURRENT_BINARY_DIR}/ground)
add_test(NAME ground_checks COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/cli/ground_checks.sh ${CLATTER_BIN}/clatter-bank
         ${bad}/ground_tiny.toml ${CLATTER_PYTHON} ${CMAKE_CURRENT_SOURCE_DIR}/cli/ground_checks.py ${ground_dir}
         ${CLATTER_MPIEXEC})
set_tests_properties(ground_checks PROPERTIES ENVIRONMENT "${CLATTER_MPI_ENV}" PROCESSORS 2 LABELS mpi TIMEOUT 600
                                              FIXTURES_SETUP ground_bank)

# The shipped configs: ground.toml is the schema's defaults (the full grid), ground-demo.toml what
# runs without -c.
add_test(NAME example_config_ground_is_schema_default COMMAND bash -c
  "diff <('${CLATTER_BIN}/clatter-bank' ground -c /dev/null --print-config) '${PROJECT_SOURCE_DIR}/configs/ground.toml' && diff <('${CLATTER_BIN}/clatter-bank' ground -c '${PROJECT_SOURCE_DIR}/configs/ground.toml' --print-config) '${PROJECT_SOURCE_DIR}/configs/ground.toml'")
add_test(NAME example_config_ground_demo_is_default COMMAND bash -c
  "diff <('${CLATTER_BIN}/clatter-bank' ground --print-config) <('${CLATTER_BIN}/clatter-bank' ground -c '${PROJECT_SOURCE_DIR}/configs/ground-demo.toml' --print-config)")
set_tests_properties(example_config_ground_is_schema_default example_config_ground_demo_is_default PROPERTIES
                     ENVIRONMENT "${CLATTER_MPI_ENV}" LABELS unit)

# The granite floor: a rock slide on granite (clatter-sim) rendered with a ground bank built for
# granite alone, both from configs/materials.toml: exit 0 and a ground stem (cli/granite_floor_checks.py).
add_test(NAME granite_floor_checks COMMAND ${expect_output} "granite floor checks: all passed" -- ${CLATTER_PYTHON}
         ${CMAKE_CURRENT_SOURCE_DIR}/cli/granite_floor_checks.py ${CLATTER_BIN}/clatter-bank ${CLATTER_BIN}/clatter-sim
         ${CLATTER_BIN}/clatter-synth ${PROJECT_SOURCE_DIR} ${CMAKE_CURRENT_BINARY_DIR}/granite_floor)
set_tests_properties(granite_floor_checks PROPERTIES ENVIRONMENT "${CLATTER_MPI_ENV}" LABELS unit TIMEOUT 120)

# Bad input: exit 2, one line naming the file, key and value, nothing written.
clatter_error_test(bad_ground_poisson 0 "ground_materials_poisson.toml:4;jelly.poisson = 0.5;must be in (-1, 0.5)"
                   ground --set ground.table=${bad_in}/ground_materials_poisson.toml --set ground.materials=jelly -o out.h5)
clatter_error_test(bad_ground_poisson_np2 2 "ground_materials_poisson.toml:4;jelly.poisson = 0.5;must be in (-1, 0.5)"
                   ground --set ground.table=${bad_in}/ground_materials_poisson.toml --set ground.materials=jelly -o out.h5)
clatter_error_test(bad_ground_youngs 0 "ground_materials_youngs.toml:3;jelly.youngs_pa = 0;must be > 0"
                   ground --set ground.table=${bad_in}/ground_materials_youngs.toml --set ground.materials=jelly -o out.h5)
clatter_error_test(bad_ground_elevation_zero 0 "--set 'ground.elevations_deg=[0, 30]';every element must be in (0, 90], not [0] = 0"
                   ground "--set=ground.elevations_deg=[0, 30]" -o out.h5)
clatter_error_test(bad_ground_elevation_file 0 "ground_bad_elevation.toml:3;'ground.elevations_deg';must be in (0, 90], not [0] = 0"
                   ground -c ${bad}/ground_bad_elevation.toml -o out.h5)
clatter_error_test(bad_ground_elevation_order 0 "ground.elevations_deg = [30, 10];[1] = 10 after 30;must ascend"
                   ground "--set=ground.elevations_deg=[30, 10]" -o out.h5)
clatter_error_test(bad_ground_eta_min 0 "--set 'ground.eta_min=0';'ground.eta_min' = '0';must be in (0, 1]"
                   ground --set ground.eta_min=0 -o out.h5)
clatter_error_test(bad_ground_eta_min_file 0 "ground_bad_eta.toml:3;'ground.eta_min' = -0.01;must be in (0, 1]"
                   ground -c ${bad}/ground_bad_eta.toml -o out.h5)
clatter_error_test(bad_ground_eta_order 0 "ground.eta_max = 0.01;must be >= ground.eta_min = 0.02"
                   ground --set ground.eta_min=0.02 --set ground.eta_max=0.01 -o out.h5)
clatter_error_test(bad_ground_unknown_material 0 "ground.materials[1] = \"lava\";unknown material 'lava';known: glass"
                   ground --set ground.materials=steel,lava -o out.h5)

# Ground bank files: bad copies of the test bank (cli/make_bad_ground_banks.py), read by info.
set(bad_ground_banks ${CMAKE_CURRENT_BINARY_DIR}/bad_ground_banks)
add_test(NAME bad_ground_banks_setup COMMAND ${CLATTER_PYTHON} ${CMAKE_CURRENT_SOURCE_DIR}/cli/make_bad_ground_banks.py
         ${ground_dir}/a.h5 ${bad_ground_banks})
set_tests_properties(bad_ground_banks_setup PROPERTIES FIXTURES_REQUIRED ground_bank FIXTURES_SETUP bad_ground_banks LABELS unit)
foreach(case
    "descending|dataset '/materials/steel/elevation_rad': [1] = 0.785|not ascending"
    "zero_dt|dataset '/materials/steel/dt_hat': [1] = 0: must be > 0 and finite"
    "nan_pi|dataset '/materials/steel/pi': [5] = nan: must be finite"
    "short_offsets|dataset '/materials/steel/series_offset': expected int64 [6] in '1', found int64 [5]"
    "gap|dataset '/materials/steel/series_offset': [1]|the series are not contiguous"
    "speed|attribute 'shear_speed_m_s' of '/materials/soil'|the moduli give"
    "poisson|attribute 'poisson' of '/materials/soil' = 0.5: must be in (0, 0.5)"
    "no_air|'/air' has no attribute 'c0_m_s'"
    "nan_tail|dataset '/materials/steel/tail': [2] [3] = nan: must be finite"
    "version1|format 'clatter-ground-bank' version 1, this build reads version 2")
  string(REPLACE "|" ";" parts "${case}")
  list(POP_FRONT parts file)
  clatter_error_test(bad_ground_bank_${file} 0 "${file}.h5;${parts}" info ${bad_ground_banks}/${file}.h5)
  set_tests_properties(bad_ground_bank_${file} PROPERTIES FIXTURES_REQUIRED bad_ground_banks)
endforeach()
