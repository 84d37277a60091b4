#include "episode.h"

void fb_episode_update(fb_episode *ep, int in_contact, double ddot, double vmin) {
  if (!in_contact) {
    ep->in_contact = 0;
    ep->state = FB_STATE_FREE;
    return;
  }
  if (!ep->in_contact) {
    ep->in_contact = 1;
    ep->restituting = 0;
    ep->v0 = ddot > vmin ? ddot : vmin;
    ep->state = ddot >= vmin ? FB_STATE_IMPACT : FB_STATE_CONTINUOUS;
    if (ep->state == FB_STATE_IMPACT) ep->impacts++;
    return;
  }
  if (ep->state != FB_STATE_IMPACT) return;
  if (ddot < 0.0) ep->restituting = 1;
  else if (ep->restituting) ep->state = FB_STATE_CONTINUOUS;
}
