# tests/unit: C unit tests, one program per module (ms_test.h reports PASS/FAIL lines).
check_PROGRAMS += tests/unit/test_base tests/unit/test_molecule tests/unit/test_formats \
	tests/unit/test_volumes tests/unit/test_image tests/unit/test_serialize \
	tests/unit/test_select tests/unit/test_ss tests/unit/test_measure tests/unit/test_scene \
	tests/unit/test_rep tests/unit/test_gl tests/unit/test_qsurf tests/unit/test_rt \
	tests/unit/test_xtc tests/unit/test_live tests/unit/test_oclrt tests/unit/test_safewrite \
	tests/unit/test_limits tests/unit/test_map tests/unit/test_pbc tests/unit/test_imd

tests_unit_test_base_SOURCES = tests/unit/test_base.c tests/unit/ms_test.h
tests_unit_test_base_LDADD = $(TEST_LIBS)
tests_unit_test_imd_SOURCES = tests/unit/test_imd.c tests/unit/ms_test.h
tests_unit_test_imd_LDADD = $(TEST_LIBS)
tests_unit_test_safewrite_SOURCES = tests/unit/test_safewrite.c tests/unit/ms_test.h
tests_unit_test_safewrite_LDADD = $(TEST_LIBS)
tests_unit_test_molecule_SOURCES = tests/unit/test_molecule.c tests/unit/ms_test.h tests/unit/ms_testload.h
tests_unit_test_molecule_LDADD = $(TEST_LIBS)
tests_unit_test_formats_SOURCES = tests/unit/test_formats.c tests/unit/ms_test.h
tests_unit_test_formats_LDADD = $(TEST_LIBS)
tests_unit_test_volumes_SOURCES = tests/unit/test_volumes.c tests/unit/ms_test.h
tests_unit_test_volumes_LDADD = $(TEST_LIBS)
tests_unit_test_image_SOURCES = tests/unit/test_image.c tests/unit/ms_test.h
tests_unit_test_image_LDADD = $(TEST_LIBS)
tests_unit_test_serialize_SOURCES = tests/unit/test_serialize.c tests/unit/ms_test.h tests/unit/ms_testload.h
tests_unit_test_serialize_LDADD = $(TEST_LIBS)
tests_unit_test_select_SOURCES = tests/unit/test_select.c tests/unit/ms_test.h tests/unit/ms_testload.h
tests_unit_test_select_LDADD = $(TEST_LIBS)
tests_unit_test_ss_SOURCES = tests/unit/test_ss.c tests/unit/ms_test.h tests/unit/ms_testload.h
tests_unit_test_ss_LDADD = $(TEST_LIBS)
tests_unit_test_measure_SOURCES = tests/unit/test_measure.c tests/unit/ms_test.h tests/unit/ms_testload.h
tests_unit_test_measure_LDADD = $(TEST_LIBS)
tests_unit_test_scene_SOURCES = tests/unit/test_scene.c tests/unit/ms_test.h
tests_unit_test_scene_LDADD = $(TEST_LIBS)
tests_unit_test_rep_SOURCES = tests/unit/test_rep.c tests/unit/ms_test.h
tests_unit_test_rep_LDADD = $(TEST_LIBS)
tests_unit_test_gl_SOURCES = tests/unit/test_gl.c tests/unit/ms_test.h
tests_unit_test_gl_LDADD = $(TEST_LIBS)
tests_unit_test_limits_SOURCES = tests/unit/test_limits.c tests/unit/ms_test.h
tests_unit_test_limits_LDADD = $(TEST_LIBS)
tests_unit_test_xtc_SOURCES = tests/unit/test_xtc.c tests/unit/ms_test.h
tests_unit_test_xtc_LDADD = $(TEST_LIBS)
tests_unit_test_qsurf_SOURCES = tests/unit/test_qsurf.c tests/unit/ms_test.h
tests_unit_test_qsurf_LDADD = $(TEST_LIBS)

# The QuickSurf sources again, built with other mesh storage types.
check_PROGRAMS += tests/unit/test_qsurf_prec
tests_unit_test_qsurf_prec_SOURCES = tests/unit/test_qsurf_prec.c tests/unit/ms_test.h \
	$(QSURF_SOURCES)
tests_unit_test_qsurf_prec_LDADD = $(TEST_LIBS)
tests_unit_test_qsurf_prec_CFLAGS = $(AM_CFLAGS) -DMS_QSURF_POS_TYPE=double \
	-DMS_QSURF_NORMAL_TYPE=float -DMS_QSURF_COLOR_TYPE=uint16_t
tests_unit_test_rt_SOURCES = tests/unit/test_rt.c tests/unit/ms_test.h
tests_unit_test_rt_LDADD = $(TEST_LIBS)
tests_unit_test_live_SOURCES = tests/unit/test_live.c tests/unit/ms_test.h
tests_unit_test_live_LDADD = $(TEST_LIBS)
# The source map, src/molscope.h, compiled with every module's header.
tests_unit_test_map_SOURCES = tests/unit/test_map.c tests/unit/ms_test.h src/molscope.h
tests_unit_test_map_LDADD = $(TEST_LIBS)
tests_unit_test_oclrt_SOURCES = tests/unit/test_rt.c tests/unit/ms_test.h
tests_unit_test_oclrt_CPPFLAGS = $(AM_CPPFLAGS) -DMS_TEST_OCLRT
tests_unit_test_oclrt_LDADD = $(TEST_LIBS)
tests_unit_test_pbc_SOURCES = tests/unit/test_pbc.c tests/unit/ms_test.h
tests_unit_test_pbc_LDADD = $(TEST_LIBS)
