#pragma once
// A registration that lasts as long as its object: destroyed, it stops (and waits for a call under
// way to return).

namespace meshmark::server {

class Subscription {
 public:
  virtual ~Subscription() = default;
};

}  // namespace meshmark::server
