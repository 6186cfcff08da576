;; Test driver: load the README's snippet, open LOGIXST_PROBE_FILE, wait for the
;; diagnostics eglot hands to flymake, ask for completion at LOGIXST_PROBE_LINE/CHAR
;; (0-based) and write both to LOGIXST_PROBE_OUT as JSON.
(let ((default-directory "/usr/share/emacs/site-lisp/elpa/"))  ; Debian's elpa-eglot
  (when (file-directory-p default-directory)
    (normal-top-level-add-subdirs-to-load-path)))
(load (getenv "LOGIXST_SNIPPET"))
(find-file (getenv "LOGIXST_PROBE_FILE"))
(run-hooks 'post-command-hook)  ; eglot-ensure connects after a command; batch has none
(let ((deadline (+ (float-time) 30)) diags labels)
  (while (and (null diags) (< (float-time) deadline))
    (accept-process-output nil 0.1)
    (setq diags (flymake-diagnostics)))
  (setq diags (mapcar (lambda (d)
                        (list (cons "code" (plist-get (cdr (assq 'eglot-lsp-diag (flymake-diagnostic-data d))) :code))
                              (cons "line" (line-number-at-pos (flymake-diagnostic-beg d)))))
                      diags))
  (goto-char (point-min))
  (forward-line (string-to-number (getenv "LOGIXST_PROBE_LINE")))
  (forward-char (string-to-number (getenv "LOGIXST_PROBE_CHAR")))
  (let* ((result (jsonrpc-request (eglot-current-server) :textDocument/completion
                                  (eglot--TextDocumentPositionParams)))
         (items (if (vectorp result) result (plist-get result :items))))
    (setq labels (mapcar (lambda (i) (list (cons "label" (plist-get i :label))
                                           (cons "detail" (or (plist-get i :detail) ""))))
                         items)))
  (with-temp-file (getenv "LOGIXST_PROBE_OUT")
    (insert (json-encode (list (cons "diagnostics" diags) (cons "completion" labels))))))
(kill-emacs 0)
