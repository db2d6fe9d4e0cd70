# src/movie: movies in one process or across MPI ranks: frame files, resuming, the
# distributed loop, the ffmpeg encoder fed in frame order, progress (the `movie` command
# itself is tcl/movie.tcl).
src_libmscore_la_SOURCES += \
	src/movie/movie.h src/movie/frames.c src/movie/encoder.c src/movie/monitor.c \
	src/movie/run.c
