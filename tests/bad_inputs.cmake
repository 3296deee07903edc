# ---- the bad-input catalogue (docs/validation.md): one test per rejected input class that the
# tests in CMakeLists.txt, synth_checks and pan_probe_checks do not already cover. Each asserts the
# exit code, the one error line and that nothing is left behind (cli/expect_error.sh).
set(bad_in ${CMAKE_CURRENT_SOURCE_DIR}/cli/bad_inputs)
set(tiny ${bad}/pan_tiny.toml)

# clatter_synth_error_test(NAME "PATTERN;PATTERN" ARGS...): clatter-synth ARGS exits 2 with one line
# naming the patterns and writes nothing. The test bank is there, so only the named input is bad.
function(clatter_synth_error_test name patterns)
  string(REPLACE ";" "|" patterns "${patterns}")
  add_test(NAME ${name} COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/cli/expect_error.sh 2
           ${CMAKE_CURRENT_BINARY_DIR}/${name} "${patterns}" -- ${CLATTER_BIN}/clatter-synth ${ARGN})
  set_tests_properties(${name} PROPERTIES LABELS unit TIMEOUT 60 FIXTURES_REQUIRED pan_bank)
endfunction()
set(good_bank ${CMAKE_CURRENT_BINARY_DIR}/pan/bank.h5)

# config: the schema step
clatter_error_test(bad_config_outside_section 0 "outside_section.toml:2;unknown key 'n_cells';belong in a [section]"
                   field -c ${bad}/outside_section.toml -o out.h5)
clatter_error_test(bad_config_unknown_section 0 "unknown_section.toml:3;unknown key 'gird.n_cells';did you mean 'grid.n_cells'"
                   field -c ${bad}/unknown_section.toml -o out.h5)
clatter_error_test(bad_config_nan 0 "nan_value.toml:3;'grid.dx_m' = nan;must be in (0, 10]" field -c ${bad}/nan_value.toml -o out.h5)
clatter_error_test(bad_config_choice 0 "bad_choice.toml:3;'object.kind' = \"cube\";must be one of ellipsoid, mesh, monopole"
                   solve -c ${bad}/bad_choice.toml -o out.h5)
clatter_error_test(bad_config_tuple 0 "--set 'proxies.list_m=[0.5, 0.3]';expected an array of 2-element arrays, e.g. [[1.0, 0.0], [0.0, 1.0]]"
                   pan "--set=proxies.list_m=[0.5, 0.3]" -o out.h5)
# config: the job's checks over several keys
clatter_error_test(bad_solve_no_fields 0 "'solve.fields' is empty" solve "--set=solve.fields=[]" -o out.h5)
clatter_error_test(bad_solve_no_listeners 0 "'listeners.points_m' is empty" solve "--set=listeners.points_m=[]" -o out.h5)
clatter_error_test(bad_pan_proxy_order 0 "'proxies.list_m' proxy 1 = [0.2, 0.3];C <= B <= A = 0.5"
                   pan "--set=proxies.list_m=[[0.2, 0.3]]" -o out.h5)
clatter_error_test(bad_pan_divisions 0 "'fit.divisions' has 12;must be 2, 4, 8, 16, 32 or 64" pan --set fit.divisions=12 -o out.h5)
clatter_error_test(bad_pan_max_directions 0 "'fit.max_directions' has 20;fewer than the layout's 45 directions" pan --set fit.max_directions=20 -o out.h5)
clatter_error_test(bad_pan_radius_inside 0 "'fit.radii_m' has 0.51: 0.5112 m from the centre, not beyond the Kirchhoff surface (radius 0.5195 m + 2 cells = 0.5325 m)"
                   pan "--set=fit.radii_m=[0.51, 1.0]" -o out.h5)
clatter_error_test(bad_pan_held_out_radius_inside 0 "'check.held_out_radii_m' has 0.51: 0.51 m from the centre, not beyond the Kirchhoff surface"
                   pan "--set=check.held_out_radii_m=[0.51, 1.0]" -o out.h5)
clatter_error_test(bad_pan_radii_order 0 "'fit.radii_m' has 0.8 after 1.001: the radii must ascend" pan "--set=fit.radii_m=[1.0, 0.8]" -o out.h5)
clatter_error_test(bad_pan_removed_key 0 "--set 'fit.terms=2': unknown key 'fit.terms'" pan "--set=fit.terms=2" -o out.h5)
clatter_error_test(bad_pan_cfl_np2 2 "'time.dt_s' = 0.0001;CFL limit" pan --set grid.dx_m=0.01 --set time.dt_s=1e-4 -o out.h5)
clatter_error_test(bad_solve_scheme 0 "--set 'solver.scheme=iwb';'solver.scheme' = 'iwb';must be one of me4, srl"
                   solve --set solver.scheme=iwb -o out.h5)
# a body given as a mesh: the file must be there, and octant mode needs its mirror symmetry
clatter_error_test(bad_solve_mesh_missing 0 "'object.mesh' = \"nowhere.obj\";cannot open the mesh file"
                   solve --set object.kind=mesh --set object.mesh=nowhere.obj -o out.h5)
clatter_error_test(bad_solve_mesh_octant_asymmetric 0 "'grid.octant' = true;tetrahedron.obj;not mirror-symmetric;grid.octant = false"
                   solve --set object.kind=mesh --set object.mesh=${bad}/tetrahedron.obj -o out.h5)
clatter_error_test(bad_solve_kirchhoff_too_close 0 "'kirchhoff.radius_m' has 0.5;at least 3 cells"
                   solve --set kirchhoff.radius_m=0.5 -o out.h5)
clatter_error_test(bad_solve_kirchhoff_listener_too_late 0 "'listeners.points_m' point 1 = [3, 0, 0];arrives there;after the record;raise time.duration_s"
                   solve --set kirchhoff.radius_m=0.6 "--set=listeners.points_m=[[3, 0, 0]]" -o out.h5)
clatter_error_test(bad_solve_far_without_surface 0 "'kirchhoff.far_directions' is given without a surface"
                   solve "--set=kirchhoff.far_directions=[[1, 0, 0]]" -o out.h5)
clatter_error_test(bad_solve_listener_in_blend 0 "'listeners.points_m' point 1 = [0.97, 0, 0];within 8 cells of the absorbing layer;grow grid.half_width_m"
                   solve "--set=listeners.points_m=[[0.97, 0, 0]]" -o out.h5)

# command-line options
clatter_error_test(bad_no_subcommand 0 "A subcommand is required;clatter-bank --help")
clatter_error_test(bad_missing_argument 0 "bank is required" info)
clatter_error_test(bad_log_level 0 "--log-level: loud not in {error,warn,info,debug}" --log-level loud field -o out.h5)
clatter_error_test(bad_slice 0 "--slice '2/2';expected K/N with 0 <= K < N" pan -c ${tiny} --slice 2/2 -o out.h5)
clatter_error_test(bad_slice_syntax 0 "--slice 'x';expected K/N" pan -c ${tiny} --slice x -o out.h5)
clatter_error_test(bad_ranks_per_task 0 "--ranks-per-task 2;divide the 1 MPI ranks" pan -c ${tiny} --ranks-per-task 2 -o out.h5)
clatter_error_test(bad_ranks_per_task_np2 2 "--ranks-per-task 3;divide the 2 MPI ranks" pan -c ${tiny} --ranks-per-task 3 -o out.h5)
clatter_error_test(bad_merge_not_results 0 "nowhere.tasks: not a sweep results folder (no sweep.toml)"
                   merge --results nowhere.tasks -o out.h5)
clatter_error_test(bad_plan_ranks 0 "--ranks 0;must be >= 1" plan -c ${tiny} --ranks 0)
clatter_error_test(bad_plan_kind 0 "--kind: no bank kind 'lamb' (known: pan, pan-object, modal, object, ground)" plan --kind lamb)
set(probe_args probe ${good_bank} --proxy 0.35,0.2 --field 1)
clatter_error_test(bad_probe_rate 0 "--rate -5;must be >= 0 Hz" ${probe_args} --point 1,0.5,0.5 --rate -5)
clatter_error_test(bad_probe_point_nan 0 "--point 1,nan,0.5;coordinates must be finite" ${probe_args} --point 1,nan,0.5)
# info and probe find a bank's kind by its format attribute (banks/registry.cpp), and refuse the
# options another kind declared
clatter_error_test(bad_probe_entry_on_pan 0 "--entry: only for a modal bank;bank.h5 is not one" ${probe_args} --point 1,0.5,0.5 --entry 0)
clatter_error_test(bad_info_entry_on_pan 0 "--entry: only for a modal bank;bank.h5 is not one" info ${good_bank} --entry 0)
clatter_error_test(bad_probe_pan_without_proxy 0 "a PAN bank needs --proxy B,C (or --mesh KEY) and --field N" probe ${good_bank} --point 1,0.5,0.5)
set_tests_properties(bad_probe_rate bad_probe_point_nan bad_probe_entry_on_pan bad_info_entry_on_pan bad_probe_pan_without_proxy
                     PROPERTIES FIXTURES_REQUIRED pan_bank)
clatter_error_test(bad_plan_ground 0 "plan: no cost model for a ground bank yet" plan -c ${PROJECT_SOURCE_DIR}/configs/ground-demo.toml)
clatter_error_test(bad_plan_empty_config 0 "plan: several of the bank kinds' schemas accept this config;--kind" plan -c ${bad}/empty.toml)
clatter_synth_error_test(bad_synth_option "not expected: --frobnicate;clatter-synth --help" -i ${bad_in}/good.json -b ${good_bank} --frobnicate)
clatter_synth_error_test(bad_synth_missing_bank "give a PAN bank (-b or -P), a modal bank (-m), an object bank (-O) or a ground bank (-g), or several" -i ${bad_in}/good.json)
clatter_synth_error_test(bad_synth_rate "--rate 100;must be in [8000, 384000] Hz" -i ${bad_in}/good.json -b ${good_bank} --rate 100)
clatter_synth_error_test(bad_synth_format "--format: mp3 not in {float,pcm24}" -i ${bad_in}/good.json -b ${good_bank} --format mp3)
clatter_synth_error_test(bad_synth_pcm24_range "--format pcm24;beyond the 24-bit range;add --normalize"
                         -i ${bad_in}/good.json -b ${good_bank} --format pcm24)

# scenes: each file is good.json with one defect
foreach(case
    "nowhere|nowhere.json: cannot open the scene file"
    "malformed|malformed.json: not valid JSON|parse error at line 4"
    "wrong_format|wrong_format.json: format: \"clatter-pan-bank\", expected \"clatter-scene\""
    "missing_key|missing_key.json: objects[0]: missing key 'mass_kg'"
    "wrong_type|wrong_type.json: objects[0].mass_kg: expected a number, found \"0.78\""
    "not_an_array|not_an_array.json: objects: expected an array, found object"
    "short_vector|short_vector.json: events[0].point_m: expected an array of 3 numbers"
    "duplicate_id|duplicate_id.json: objects[1].id: 1 is used twice"
    "huge_id|huge_id.json: objects[0].id: 4294967297: must be an integer in [1, 2147483647]"
    "bad_poisson|bad_poisson.json: materials.rock.poisson_ratio: 0.5: must be in (-1, 0.5)"
    "unknown_ground|unknown_ground.json: ground_material: \"lava\" is not in materials"
    "lifetime|lifetime.json: objects[1].destroyed_s: 0.2: must be after created_s = 0.5"
    "quaternion|quaternion.json: events[0].pose_a.orientation_wxyz|has norm 1.118|must be a unit quaternion"
    "negative_time|negative_time.json: events[0]: time -0.01 s: must be >= 0"
    "normal_speed|normal_speed.json: events[0]: normal speed 0 m/s: must be > 0"
    "self_collision|self_collision.json: events[0]: object 1 collides with itself"
    "no_listeners|no_listeners.json: listeners: expected at least one listener"
    "base_frequency|base_frequency.json: objects[0].base_frequency_hz: 0: must be > 0"
    "half_damping|half_damping.json: materials.rock: give both rayleigh_alpha_1_s and rayleigh_beta_s, or neither"
    "fracture_time|fracture_time.json: events[0]: missing key 'contact_time_s'"
    "contact_both|contact_both.json: events[0]: a contact event needs exactly one of normal_speed_m_s and contact_time_s"
    "sustained_time|sustained_time.json: events[0]: contact_time_s 0 s: must be > 0"
    "density|density.json: materials.concrete.density_kg_m3: -5: must be > 0")
  string(REPLACE "|" ";" parts "${case}")
  list(POP_FRONT parts file)
  clatter_synth_error_test(bad_scene_${file} "${parts}" -i ${bad_in}/${file}.json -b ${good_bank})
endforeach()

# modal banks (the sphere bank of the synth_modal_bank fixture): no bank for the material's nu, a
# material without damping, banks of the wrong kind either way, no bank at all
set(modal_bank ${CMAKE_CURRENT_BINARY_DIR}/synth_sphere/modal.h5)
clatter_synth_error_test(bad_modal_no_bank "good.json: objects[0]: material 'rock' (poisson_ratio 0.25) has no modal bank;glass (nu 0.2"
                         -i ${bad_in}/good.json -m ${modal_bank})
clatter_synth_error_test(bad_modal_no_damping "no_damping.json: materials.rock: modal sound needs rayleigh_alpha_1_s and rayleigh_beta_s"
                         -i ${bad_in}/no_damping.json -m ${modal_bank})
clatter_synth_error_test(bad_modal_pan_kind "bank.h5: format 'clatter-pan-bank', expected 'clatter-modal-bank'" -i ${bad_in}/good.json -m ${good_bank})
clatter_synth_error_test(bad_pan_modal_kind "modal.h5: format 'clatter-modal-bank', expected 'clatter-pan-bank'" -i ${bad_in}/good.json -b ${modal_bank})
set_tests_properties(bad_modal_no_bank bad_modal_no_damping bad_modal_pan_kind bad_pan_modal_kind
                     PROPERTIES FIXTURES_REQUIRED "pan_bank;synth_modal_bank")

# OBJ meshes: box.json with box.obj replaced by a broken one
foreach(case
    "mesh_bad_index|mesh_bad_index.obj:15: face corner 9 is not one of the 8 vertices"
    "mesh_nan|mesh_nan.obj:9: vertex coordinate is nan: must be finite"
    "mesh_flipped|mesh_flipped.obj:15: edge 6-8 runs the same way in the face on line 11"
    "mesh_nonmanifold|mesh_nonmanifold.obj:17: edge 5-6 runs the same way|more than two meet at that edge"
    "mesh_repeated|mesh_repeated.obj:15: face repeats vertex 4"
    "mesh_few|mesh_few.obj: 2 triangles: a closed mesh needs at least 4")
  string(REPLACE "|" ";" parts "${case}")
  list(POP_FRONT parts file)
  clatter_synth_error_test(bad_${file} "objects[0].mesh;${parts}" -i ${bad_in}/${file}.json -b ${good_bank})
endforeach()

# James-lab impulse files, read with side.json (good.json without events)
foreach(case
    "nowhere|impulses_nowhere.txt: cannot open the impulse file"
    "letter|impulses_letter.txt:2: 'X': expected C (object-ground) or P (object pair)"
    "short|impulses_short.txt:2: missing direction n"
    "extra|impulses_extra.txt:2: unexpected '7' after the direction n"
    "word|impulses_word.txt:2: impulse J 'heavy' is not a number"
    "unknown|impulses_unknown.txt:2: object 9 is not in the scene's objects"
    "nan|impulses_nan.txt:2: impulse J is nan: must be finite")
  string(REPLACE "|" ";" parts "${case}")
  list(POP_FRONT parts file)
  clatter_synth_error_test(bad_impulses_${file} "${parts}" -i ${bad_in}/side.json --impulses ${bad_in}/impulses_${file}.txt
                           -b ${good_bank})
endforeach()

# The good inputs the bad ones are made from render, so each bad test fails for its one defect.
add_test(NAME bad_inputs_good_ones COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/cli/good_inputs.sh ${CLATTER_BIN} ${bad_in} ${good_bank}
         ${tiny} ${CMAKE_CURRENT_BINARY_DIR}/good_inputs)
set_tests_properties(bad_inputs_good_ones PROPERTIES FIXTURES_REQUIRED pan_bank ENVIRONMENT "${CLATTER_MPI_ENV}" LABELS unit TIMEOUT 60)

# PAN bank files: bad copies of the test bank (cli/make_bad_banks.py), read by clatter-synth and info
set(bad_banks ${CMAKE_CURRENT_BINARY_DIR}/bad_banks)
add_test(NAME bad_banks_setup COMMAND ${CLATTER_PYTHON} ${CMAKE_CURRENT_SOURCE_DIR}/cli/make_bad_banks.py ${good_bank} ${bad_banks})
set_tests_properties(bad_banks_setup PROPERTIES FIXTURES_REQUIRED pan_bank FIXTURES_SETUP bad_banks LABELS unit)
foreach(case
    "missing|missing.h5: no such file"
    "not_hdf5|not_hdf5.h5: not a readable HDF5 file"
    "truncated|truncated.h5: not a readable HDF5 file"
    "no_format|no_format.h5: not a Clatter file (no 'format' attribute)|expected format 'clatter-pan-bank'"
    "wrong_format|wrong_format.h5: format 'clatter-fdtd-raw', expected 'clatter-pan-bank'"
    "wrong_version|wrong_version.h5: format 'clatter-pan-bank' version 1, this build reads versions 5 and 6"
    "wrong_shape|wrong_shape.h5: dataset '/proxies/c_m': expected float64 [2] in 'm', found float64 [1]"
    "corrupt|corrupt.h5: dataset '/coefficients/values' cannot be read: corrupt or truncated file"
    "index_out_of_range|index_out_of_range.h5: '/directions' set 0 (proxy 0, field 1): '/coefficients/index_delta' gives coefficient index 512 outside [0, 512)")
  string(REPLACE "|" ";" parts "${case}")
  list(POP_FRONT parts file)
  clatter_synth_error_test(bad_bank_${file} "${parts}" -i ${bad_in}/good.json -b ${bad_banks}/${file}.h5)
  set_tests_properties(bad_bank_${file} PROPERTIES FIXTURES_REQUIRED "pan_bank;bad_banks")
endforeach()
clatter_error_test(bad_bank_info_corrupt 0 "corrupt.h5;cannot be read: corrupt or truncated file" info ${bad_banks}/corrupt.h5)
clatter_error_test(bad_bank_info_version 0 "wrong_version.h5;version 1, this build reads versions 5 and 6" info ${bad_banks}/wrong_version.h5)
clatter_error_test(bad_bank_info_wrong_format 0 "wrong_format.h5: format 'clatter-fdtd-raw' is not a bank's;clatter-pan-bank, clatter-modal-bank, clatter-object-bank, clatter-ground-bank"
                   info ${bad_banks}/wrong_format.h5)
clatter_error_test(bad_bank_info_no_format 0 "no_format.h5: not a Clatter file (no 'format' attribute);expected a bank"
                   info ${bad_banks}/no_format.h5)
set_tests_properties(bad_bank_info_corrupt bad_bank_info_version bad_bank_info_wrong_format bad_bank_info_no_format
                     PROPERTIES FIXTURES_REQUIRED bad_banks)

# sweep results folders (cli/make_bad_results.sh)
set(bad_results ${CMAKE_CURRENT_BINARY_DIR}/bad_results)
add_test(NAME bad_results_setup COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/cli/make_bad_results.sh ${CLATTER_BIN}/clatter-bank ${tiny} ${bad_results})
set_tests_properties(bad_results_setup PROPERTIES FIXTURES_SETUP bad_results ENVIRONMENT "${CLATTER_MPI_ENV}" LABELS unit)
clatter_error_test(bad_results_other_config 0 "--results ${bad_results}/other.tasks: holds a sweep of another config"
                   pan -c ${tiny} --results ${bad_results}/other.tasks -o out.h5)
clatter_error_test(bad_results_without_resume 0 "present.tasks: already holds 1 of this sweep's task files;add --resume"
                   pan -c ${tiny} --results ${bad_results}/present.tasks -o out.h5)
clatter_error_test(bad_results_no_kind 0 "nokind.tasks/sweep.toml: line 1 must name the bank kind;add that line"
                   merge --results ${bad_results}/nokind.tasks -o out.h5)
set_tests_properties(bad_results_other_config bad_results_without_resume bad_results_no_kind PROPERTIES FIXTURES_REQUIRED bad_results)
# Accepted, not refused: an unreadable task file is redone on --resume and the bank is written.
add_test(NAME bad_results_corrupt_task_redone COMMAND ${expect_output}
         "warning: sweep: redoing p000-f1: .*p000-f1.h5: not a readable HDF5 file" "merge: wrote .*corrupt.h5 \\(1 of 1 tasks"
         -- ${CLATTER_BIN}/clatter-bank pan -c ${tiny} --results ${bad_results}/corrupt.tasks -o ${bad_results}/corrupt.h5
         --resume --progress-interval 0)
set_tests_properties(bad_results_corrupt_task_redone PROPERTIES FIXTURES_REQUIRED bad_results ENVIRONMENT "${CLATTER_MPI_ENV}"
                                                     LABELS unit)

# the modal bank's config (banks/modal/modal_spec.cpp) and its materials table (io/materials.cpp)
set(one_sphere "--set=patch.samples=[[0.5773502691896258, 0.5773502691896258, 0.5773502691896258]]")
clatter_error_test(bad_modal_unknown_material 0 "unknown material 'unobtainium';known: glass"
                   modal --set material.name=unobtainium -o out.h5)
clatter_error_test(bad_modal_poisson 0 "materials_bad_poisson.toml:5;rubberish.poisson = 0.5;(-1, 0.5)"
                   modal --set material.table=${bad_in}/materials_bad_poisson.toml --set material.name=rubberish -o out.h5)
# a material of the table without Rayleigh damping (a ground's) has no modal bank
clatter_error_test(bad_modal_undamped_material 0 "configs/materials.toml (built in): [soil]: missing key 'rayleigh_alpha_1_s'"
                   modal --set material.name=soil -o out.h5)
clatter_error_test(bad_modal_no_table 0 "no_such_table.toml;cannot open materials file"
                   modal --set material.table=no_such_table.toml -o out.h5)
clatter_error_test(bad_modal_axes_order 0 "patch.samples[0] = [0.7, 0.5, 0.5];not ascending (a <= b <= c): 0.7, 0.5, 0.5"
                   modal "--set=patch.samples=[[0.7, 0.5, 0.5]]" -o out.h5)
clatter_error_test(bad_modal_off_sphere 0 "patch.samples[0];off the unit sphere"
                   modal "--set=patch.samples=[[0.5, 0.5, 0.5]]" -o out.h5)
clatter_error_test(bad_modal_below_min_ratio 0 "patch.samples[0];below min_ratio 0.025"
                   modal "--set=patch.samples=[[0.015, 0.7, 0.7139852939661994]]" -o out.h5)
# a/c = 0.06 is above min_ratio, but a needle with b/c = 0.06 lies beyond the cigar (b/c = 0.1).
clatter_error_test(bad_modal_beyond_cigar 0 "patch.samples[0];beyond the patch's edge from the cigar (b/c = 0.1)"
                   modal "--set=patch.samples=[[0.06, 0.06, 0.996393496566492]]" -o out.h5)
clatter_error_test(bad_modal_zero_axis 0 "'patch.samples';every element must be in (0, 1]"
                   modal "--set=patch.samples=[[0, 0.7071067811865476, 0.7071067811865476]]" -o out.h5)
clatter_error_test(bad_modal_duplicate_sample 0 "patch.samples[1];the same ellipsoid as patch.samples[0]"
                   modal "--set=patch.samples=[[0.5773502691896258, 0.5773502691896258, 0.5773502691896258], [0.5773502691896258, 0.5773502691896258, 0.5773502691896258]]" -o out.h5)
clatter_error_test(bad_modal_no_samples 0 "patch.samples = [];at least one ellipsoid" modal "--set=patch.samples=[]" -o out.h5)
clatter_error_test(bad_modal_residual_limit 0 "solver.residual_limit = 1e-12;must exceed solver.tolerance"
                   modal --set solver.residual_limit=1e-12 -o out.h5)
clatter_error_test(bad_modal_nev_per_shift 0 "solver.nev_per_shift = 8;at least 10"
                   modal --set solver.nev_per_shift=8 -o out.h5)
clatter_error_test(bad_modal_min_ratio_one_np2 2 "'patch.min_ratio' = '1';must be in (0, 1)" modal --set patch.min_ratio=1 -o out.h5)
# pan-object (per-object PAN): the meshes
clatter_error_test(bad_pan_object_no_meshes 0 "'objects.meshes' is empty;at least one mesh" pan-object -o out.h5)
clatter_error_test(bad_pan_object_missing 0 "'objects.meshes' entry 1 = 'nowhere.obj';cannot open the mesh file"
                   pan-object "--set=objects.meshes=[\"nowhere.obj\"]" -o out.h5)
clatter_error_test(bad_pan_object_twice 0 "'objects.meshes' entry 2;octahedron.obj;the same mesh as entry 1"
                   pan-object "--set=objects.meshes=[\"${bad}/octahedron.obj\", \"${bad}/octahedron.obj\"]" -o out.h5)
