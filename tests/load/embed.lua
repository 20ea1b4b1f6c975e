-- wrk script: POST /v1/models/{id}/embed with a fresh recipient each time, so the daemon assigns
-- a new payload per request. Set by load_test.sh: MODEL (model id) and TOKEN (API key).
-- Like a well-behaved client, a connection that got 503 (queue full) waits before trying again
-- (100 ms rather than the whole Retry-After, to keep the queue full).
local model = os.getenv("MODEL")
local token = os.getenv("TOKEN")
local threads = {}

function setup(thread)
  thread:set("tid", #threads + 1)
  table.insert(threads, thread)
end

function init(args)
  counter = 0
  accepted = 0
  refused = 0
  backoff = 0
end

function delay()
  return backoff
end

function request()
  counter = counter + 1
  local body = string.format('{"recipient":"load-%d-%d","format":"ply"}', tid, counter)
  return wrk.format("POST", "/v1/models/" .. model .. "/embed",
                    {["Authorization"] = "Bearer " .. token, ["Content-Type"] = "application/json"}, body)
end

function response(status, headers, body)
  backoff = 0
  if status == 202 then accepted = accepted + 1 elseif status == 503 then refused = refused + 1; backoff = 100 end
end

function done(summary, latency, requests)
  local a, r = 0, 0
  for _, t in ipairs(threads) do
    a = a + t:get("accepted")
    r = r + t:get("refused")
  end
  io.write(string.format("embed requests: %d answered, %d accepted (202), %d queue full (503)\n",
                         summary.requests, a, r))
end
