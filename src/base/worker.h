/* A forked worker process (an ensemble's members, a sweep's points) that
 * lives only as long as its parent and holds nothing of the parent's but
 * its own pipe. */
#ifndef FB_WORKER_H
#define FB_WORKER_H

#include <stddef.h>
#include <sys/types.h>

/* Called first in the child after fork(): the kernel ends this process with
 * SIGKILL when its parent dies (prctl PR_SET_PDEATHSIG; a parent that died
 * before the call is caught by getppid() != parent); SIGINT, SIGTERM and
 * SIGHUP take their default action unless ignored (the parent's clean-up
 * handlers are the parent's); every file descriptor but 0, 1, 2 and keep_fd is closed
 * (close_range), so no lock of the parent (an output folder's flock, a
 * baseline's) outlives the parent in a worker. Returns 0, or -1 when the
 * worker must _exit at once (its parent is gone or the call failed). */
int fb_worker_tie_to_parent(pid_t parent, int keep_fd);

/* Writes all n bytes of p to fd (a worker's pipe), again after EINTR and
 * a short write. Returns 1, or 0 when a write failed or wrote nothing. */
int fb_worker_write_all(int fd, const void *p, size_t n);

/* Reads n bytes from fd into p, again after EINTR and a short read.
 * Returns 1, or 0 on a failed read or end of file before n bytes. */
int fb_worker_read_all(int fd, void *p, size_t n);

#endif
